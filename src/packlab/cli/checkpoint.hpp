// Checkpoints of the commands that can run for minutes and resume with `--resume DIR`
// (generate fba, generate bd, shake, relax, test compress, test shear, calibrate compress,
// calibrate shear; generate vem keeps its own format, generate/vem.hpp).
//
// DIR/checkpoint.bin is written atomically (io::write_atomically: a kill -9 leaves the previous
// checkpoint or the new one, never half of one) every output.checkpoint_seconds of wall time
// and, for most, at the end of the run (test compress --solver static: at its fresh
// factorizations only, mechanics/static_compression.cpp). Layout: the magic "PLCKPT01" (the format version), then one
// checksummed section (binary::write_checked: size, FNV-1a hash, bytes) holding the command's
// name, its settings (io::ConfigSchema::values() as JSON text), the input file and the state of
// the method, which the method writes itself at a point between two of its iterations. A file
// that is damaged, truncated, of another version or of another command is refused with one
// InputError (exit code 2). A resumed run takes its settings from the checkpoint, so that it
// goes on exactly as the interrupted one would have.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <ostream>
#include <sstream>
#include <string>

#include "packlab/io/config.hpp"
#include "packlab/mechanics/calibration.hpp"

namespace packlab::cli {

// The file a resumable command keeps in its output folder.
std::filesystem::path checkpoint_path(const std::filesystem::path& dir);

void write_command_checkpoint(const std::filesystem::path& dir, const io::ConfigSchema& settings,
                              const std::string& input, const std::function<void(std::ostream&)>& state);

// What read_command_checkpoint() found besides the settings: the input file of the run and the
// stream positioned at the method's state.
struct SavedRun {
  std::string input;
  std::istringstream state;
};
// Reads DIR/checkpoint.bin of the command `settings.command()` and puts the saved settings into
// the targets of `settings`. InputError when there is none or it is damaged.
SavedRun read_command_checkpoint(const std::filesystem::path& dir, const io::ConfigSchema& settings);

// Writes the checkpoint when `seconds` of wall time have passed since the last one (or the
// start), and on demand at the end.
//
// Test hook: with PACKLAB_KILL_AFTER_CHECKPOINTS=N in the environment the process kills itself
// with SIGKILL right after its N-th checkpoint (a kill -9 at a known point, so that the resume
// tests interrupt a run at the same place every time, however fast the machine is).
class CheckpointWriter {
 public:
  CheckpointWriter(std::filesystem::path dir, const io::ConfigSchema& settings, std::string input, double seconds)
      : dir_(std::move(dir)), settings_(settings), input_(std::move(input)), seconds_(seconds) {}
  void write_if_due(const std::function<void(std::ostream&)>& state);
  void write(const std::function<void(std::ostream&)>& state);

 private:
  std::filesystem::path dir_;
  const io::ConfigSchema& settings_;
  std::string input_;
  double seconds_;
  long written_ = 0;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// A resumable calibration (calibrate compress, calibrate shear) wired to the command's
// checkpoint: one after every finished simulation and one every checkpoint_seconds within a
// simulation (the dynamic solvers, and the static one at its fresh factorizations). The state is the finished
// evaluations, then whether a simulation was running, its parameters and the test's own state.
// With `resumed`, the returned progress replays the saved evaluations and hands the running
// simulation's state to the test (mechanics::CalibrationProgress); `resumed` must outlive it.
mechanics::CalibrationProgress calibration_progress(CheckpointWriter& writer, SavedRun* resumed);

}  // namespace packlab::cli
