// Outputs are never half-written: content goes to a temporary name in the same folder and is
// renamed over the target only after it was written and flushed without error.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

namespace packlab::io {

// Calls write(stream) on a temporary file beside `path`, then renames it to `path`.
// On any failure the temporary is removed and InputError is thrown naming the path.
void write_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

void write_text_atomically(const std::filesystem::path& path, const std::string& text);

// Creates `dir` (and parents); InputError if it exists as a non-directory or cannot be made.
void ensure_directory(const std::filesystem::path& dir);

// The output folder of a command, made by ensure_directory() at construction. A command that
// fails (an exception leaves the scope) before anything was written into a folder it made
// removes it again, so that bad input found only once the run starts (a model without bonds, a
// bad file among several) leaves no empty folder behind. A folder that already existed, or
// holds anything (a checkpoint to resume from, outputs for inspection), stays.
class OutputFolder {
 public:
  explicit OutputFolder(std::filesystem::path dir);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

 private:
  std::filesystem::path dir_;
  bool created_ = false;
  int exceptions_ = 0;  // uncaught at construction
};

// Checks before a long run that `path` can be written: not a folder, its folder exists and
// takes a new file. InputError naming the path otherwise; nothing is left behind.
void check_writable_file(const std::filesystem::path& path);

}  // namespace packlab::io
