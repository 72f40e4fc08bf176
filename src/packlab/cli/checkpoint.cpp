#include "packlab/cli/checkpoint.hpp"

#include <fmt/format.h>

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <vector>

#include "packlab/cli/options.hpp"
#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/io/atomic_file.hpp"

namespace packlab::cli {

namespace {

constexpr std::uint64_t checkpoint_magic = 0x313054504B434C50ULL;  // "PLCKPT01" in the file (little-endian)

}  // namespace

std::filesystem::path checkpoint_path(const std::filesystem::path& dir) { return dir / "checkpoint.bin"; }

void write_command_checkpoint(const std::filesystem::path& dir, const io::ConfigSchema& settings,
                              const std::string& input, const std::function<void(std::ostream&)>& state) {
  io::write_atomically(checkpoint_path(dir), [&](std::ostream& out) {
    binary::write(out, checkpoint_magic);
    binary::write_checked(out, [&](std::ostream& section) {
      binary::write_string(section, settings.command());
      const std::string values = settings.values().dump();
      binary::write_vector(section, std::vector<char>(values.begin(), values.end()));
      binary::write_string(section, input);
      state(section);
    });
    if (!out) fail_input(fmt::format("{}: write failed", checkpoint_path(dir).string()));
  });
}

SavedRun read_command_checkpoint(const std::filesystem::path& dir, const io::ConfigSchema& settings) {
  const std::filesystem::path path = checkpoint_path(dir);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail_input(fmt::format("--resume = {}: no checkpoint.bin in this folder", dir.string()));
  // One message for every way a checkpoint can be bad, naming the file.
  try {
    std::uint64_t magic = 0;
    binary::read(in, magic, "header");
    binary::require_header(magic, checkpoint_magic, "not a packlab checkpoint");
    SavedRun run{"", binary::read_checked(in, "the saved run")};
    std::string command;
    binary::read_string(run.state, command, "command");
    if (command != settings.command())
      fail_input(fmt::format("written by packlab {}, not packlab {}", command, settings.command()));
    std::vector<char> values;
    binary::read_vector(run.state, values, "settings", 1 << 24);
    const nlohmann::json saved = nlohmann::json::parse(values.begin(), values.end(), nullptr, false);
    if (saved.is_discarded()) fail_input("checkpoint is damaged: settings");
    // Keys added since the run was saved take the value it ran with (ConfigSchema::when_not_saved).
    settings.set_values(saved, "saved settings");
    binary::read_string(run.state, run.input, "input file");
    return run;
  } catch (const InputError& error) {
    fail_input(fmt::format("--resume = {}: {}: {}", dir.string(), path.filename().string(), error.what()));
  }
}

SavedRun resume_saved_run(const OptionFlags& flags, const std::string& dir, const std::string& in,
                          const std::string& out) {
  std::string refused = flags.config_file().empty() ? flags.first_given({"threads", "adapt_threads"}) : "--config";
  if (refused.empty() && !in.empty()) refused = "the input file";
  if (!refused.empty())
    fail_input(fmt::format("{} cannot be combined with --resume: the run continues with its saved settings", refused));
  if (!out.empty() && std::filesystem::path(out) != std::filesystem::path(dir))
    fail_input("--out: a resumed run writes into its own folder (--resume DIR); drop --out");
  SavedRun run = read_command_checkpoint(dir, flags.schema());
  flags.apply();  // --threads and --adapt-threads, the only flags left
  return run;
}

void CheckpointWriter::write_if_due(const std::function<void(std::ostream&)>& state) {
  if (std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count() >= seconds_) write(state);
}

void CheckpointWriter::write(const std::function<void(std::ostream&)>& state) {
  write_command_checkpoint(dir_, settings_, input_, state);
  last_ = std::chrono::steady_clock::now();
  ++written_;
  if (const char* kill_after = std::getenv("PACKLAB_KILL_AFTER_CHECKPOINTS"))
    if (std::atol(kill_after) == written_) ::raise(SIGKILL);
}

namespace {

void write_evaluations(std::ostream& out, const std::vector<mechanics::CalibrationStep>& done) {
  binary::write(out, static_cast<std::uint64_t>(done.size()));
  for (const mechanics::CalibrationStep& step : done) {
    binary::write(out, static_cast<std::uint8_t>(step.finite_difference ? 1 : 0));
    binary::write_vector(out, step.parameters);
    binary::write_vector(out, step.responses);
  }
}

}  // namespace

mechanics::CalibrationProgress calibration_progress(CheckpointWriter& writer, SavedRun* resumed) {
  mechanics::CalibrationProgress progress;
  if (resumed != nullptr) {
    std::istream& in = resumed->state;
    std::uint64_t count = 0;
    binary::read(in, count, "evaluations");
    if (count > 100000) fail_input("checkpoint is damaged: implausible number of evaluations");
    for (std::uint64_t k = 0; k < count; ++k) {
      mechanics::CalibrationStep step;
      std::uint8_t finite_difference = 0;
      binary::read(in, finite_difference, "evaluation");
      binary::read_vector(in, step.parameters, "evaluation parameters", 64);
      binary::read_vector(in, step.responses, "evaluation responses", 64);
      step.finite_difference = finite_difference != 0;
      progress.done.push_back(std::move(step));
    }
    std::uint8_t running = 0;
    binary::read(in, running, "running simulation");
    if (running != 0) {
      binary::read_vector(in, progress.running, "running parameters", 64);
      progress.running_state = &in;
    }
  }
  // The evaluations finished so far, shared by the two writers below.
  auto done = std::make_shared<std::vector<mechanics::CalibrationStep>>(progress.done);
  progress.on_evaluation = [&writer, done](const std::vector<mechanics::CalibrationStep>& evaluations) {
    *done = evaluations;
    writer.write([&](std::ostream& out) {
      write_evaluations(out, *done);
      binary::write(out, std::uint8_t{0});
    });
  };
  progress.checkpoint = [&writer, done](const std::vector<double>& parameters,
                                        const std::function<void(std::ostream&)>& state) {
    writer.write_if_due([&](std::ostream& out) {
      write_evaluations(out, *done);
      binary::write(out, std::uint8_t{1});
      binary::write_vector(out, parameters);
      state(out);
    });
  };
  return progress;
}

}  // namespace packlab::cli
