// --resume of generate fba, generate bd, generate ls, generate scrm and shake (cli/checkpoint.hpp): a run killed with
// SIGKILL once it has written a checkpoint and resumed gives the packing of an uninterrupted
// run bit for bit; a damaged checkpoint, a missing one and a changed setting are refused with
// exit code 2 and one message.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_runner.hpp"

namespace {

using packlab::test::run_packlab;
using packlab::test::TempDir;

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Starts `packlab ARGS --out DIR` in the background, kills it with SIGKILL as soon as DIR holds
// a checkpoint (or lets it end), then resumes it; returns the resumed run's exit code and output.
packlab::test::CliResult kill_and_resume(const std::string& args, const std::string& dir, const std::string& resume) {
  const std::string script = fmt::format(
      "{} {} --out {} --checkpoint-seconds 1e-6 --quiet --no-plots >/dev/null 2>&1 & pid=$!; "
      "while [ ! -e {}/checkpoint.bin ] && kill -0 $pid 2>/dev/null; do sleep 0.005; done; "
      "kill -9 $pid 2>/dev/null; wait $pid; true",
      PACKLAB_BINARY, args, dir, dir);
  EXPECT_EQ(std::system(fmt::format("bash -c '{}'", script).c_str()), 0);
  return run_packlab(resume + " --resume " + dir + " --quiet --no-plots");
}

// `resume_args` go to the resumed runs only (e.g. another --threads: the result must not change).
void expect_resumed_run_equals_straight_run(const std::string& command, const std::string& args, const TempDir& dir,
                                            const std::string& input = "", const std::string& resume_args = "") {
  const auto straight =
      run_packlab(command + " " + input + " " + args + " --quiet --no-plots --out " + dir.file("straight"));
  ASSERT_EQ(straight.exit_code, 0) << straight.output;
  const auto resumed =
      kill_and_resume(command + " " + input + " " + args, dir.file("killed"), command + " " + resume_args);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const std::string expected = read_bytes(dir.path() / "straight" / "packing.xyz");
  ASSERT_FALSE(expected.empty());
  EXPECT_EQ(read_bytes(dir.path() / "killed" / "packing.xyz"), expected) << command;
  // Resuming a finished run writes the same outputs again.
  const auto again =
      run_packlab(command + " " + resume_args + " --resume " + dir.file("killed") + " --quiet --no-plots");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(read_bytes(dir.path() / "killed" / "packing.xyz"), expected) << command;
}

}  // namespace

TEST(ResumeCli, GenerateFbaKilledAndResumedEqualsUninterruptedRun) {
  TempDir dir("resume-fba");
  expect_resumed_run_equals_straight_run("generate fba",
                                         "--particles 400 --sizes 1,0.6 --porosity 0.4 --periodic xy --seed 3", dir);
}

TEST(ResumeCli, GenerateBdKilledAndResumedEqualsUninterruptedRun) {
  TempDir dir("resume-bd");
  expect_resumed_run_equals_straight_run(
      "generate bd", "--particles 200 --surface-potential 15e-3 --duration 0.05 --samples 20 --msd --seed 3", dir, "",
      "--threads 2");  // straight on 1 thread, resumed on 2
}

TEST(ResumeCli, GenerateLsKilledAndResumedEqualsUninterruptedRun) {
  TempDir dir("resume-ls");
  expect_resumed_run_equals_straight_run("generate ls", "--phi 0.55 --particles 300 --growth-rate 0.1 --seed 3", dir);
}

TEST(ResumeCli, GenerateScrmKilledAndResumedEqualsUninterruptedRun) {
  TempDir dir("resume-scrm");
  expect_resumed_run_equals_straight_run(
      "generate scrm", "--phi 0.5 --particles 300 --growth-rate 0.1 --final-shakes 4 --adaptive --seed 2", dir);
}

TEST(ResumeCli, ShakeKilledAndResumedEqualsUninterruptedRun) {
  TempDir dir("resume-shake");
  const auto ls = run_packlab(
      "generate ls --phi 0.5 --particles 300 --growth-rate 0.1 --seed 2 --quiet --no-plots --out " + dir.file("ls"));
  ASSERT_EQ(ls.exit_code, 0) << ls.output;
  expect_resumed_run_equals_straight_run("shake", "--sweeps 6 --adaptive --seed 4", dir, dir.file("ls/packing.xyz"));
}

TEST(ResumeCli, DamagedMissingOrForeignCheckpointAndChangedSettingsExitWithCodeTwo) {
  TempDir dir("resume-bad");
  const auto run = run_packlab("generate fba --particles 200 --seed 1 --quiet --no-plots --out " + dir.file("fba"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::filesystem::path checkpoint = dir.path() / "fba" / "checkpoint.bin";
  const std::string bytes = read_bytes(checkpoint);
  ASSERT_GT(bytes.size(), 100u);

  // One flipped byte anywhere: refused by the checksum (or the header).
  for (std::size_t k : {std::size_t{3}, std::size_t{20}, bytes.size() / 2, bytes.size() - 1}) {
    std::string damaged = bytes;
    damaged[k] = static_cast<char>(damaged[k] ^ 0x04);
    std::ofstream(checkpoint, std::ios::binary) << damaged;
    const auto r = run_packlab("generate fba --resume " + dir.file("fba"));
    EXPECT_EQ(r.exit_code, 2) << "byte " << k << ": " << r.output;
    EXPECT_NE(r.output.find("checkpoint.bin"), std::string::npos) << r.output;
  }
  std::ofstream(checkpoint, std::ios::binary) << bytes.substr(0, bytes.size() / 3);
  const auto truncated = run_packlab("generate fba --resume " + dir.file("fba"));
  EXPECT_EQ(truncated.exit_code, 2) << truncated.output;
  EXPECT_NE(truncated.output.find("truncated"), std::string::npos) << truncated.output;

  // Another command's checkpoint, none at all, a setting given with --resume.
  std::ofstream(checkpoint, std::ios::binary) << bytes;
  const auto foreign = run_packlab("generate ls --resume " + dir.file("fba"));
  EXPECT_EQ(foreign.exit_code, 2) << foreign.output;
  EXPECT_NE(foreign.output.find("not packlab generate ls"), std::string::npos) << foreign.output;
  const auto missing = run_packlab("shake --resume " + dir.path().string());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("no checkpoint.bin"), std::string::npos) << missing.output;
  const auto changed = run_packlab("generate fba --resume " + dir.file("fba") + " --porosity 0.5");
  EXPECT_EQ(changed.exit_code, 2) << changed.output;
  EXPECT_NE(changed.output.find("--porosity cannot be combined with --resume"), std::string::npos) << changed.output;
  const auto threads = run_packlab("generate fba --resume " + dir.file("fba") + " --threads 2 --quiet --no-plots");
  EXPECT_EQ(threads.exit_code, 0) << threads.output;
  const auto no_out = run_packlab("generate fba --particles 10");
  EXPECT_EQ(no_out.exit_code, 2) << no_out.output;
  EXPECT_NE(no_out.output.find("--out: required"), std::string::npos) << no_out.output;
}
