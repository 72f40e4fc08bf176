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
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& write);

void write_text_atomically(const std::filesystem::path& path, const std::string& text);

// Creates `dir` (and parents); InputError if it exists as a non-directory or cannot be made.
void ensure_directory(const std::filesystem::path& dir);

}  // namespace packlab::io
