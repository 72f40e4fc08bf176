// --resume of the DEM commands: test compress, test shear (dynamic solver), relax
// (--checkpoint DIR), calibrate compress and calibrate shear. Each run is killed with SIGKILL right after a chosen
// checkpoint (the PACKLAB_KILL_AFTER_CHECKPOINTS hook of cli/checkpoint.hpp: the same place on any machine), its resume
// killed again, and the second resume run to the end: every result file equals the one of an uninterrupted run bit for
// bit (report.json up to its wall-clock times and thread count). A damaged checkpoint and a changed output are refused
// with exit code 2.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "cli_runner.hpp"

namespace {

using packlab::test::CliResult;
using packlab::test::run_packlab;
using packlab::test::TempDir;
namespace fs = std::filesystem;

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `packlab ARGS` killed by SIGKILL right after its `checkpoints`-th checkpoint.
CliResult run_killed(const std::string& args, int checkpoints) {
  // The child inherits the environment: the hook is set around run_packlab only.
  ::setenv("PACKLAB_KILL_AFTER_CHECKPOINTS", std::to_string(checkpoints).c_str(), 1);
  CliResult result = run_packlab(args);
  ::unsetenv("PACKLAB_KILL_AFTER_CHECKPOINTS");
  return result;
}

// The report without what may differ between runs of the same result: wall-clock times (every
// key that names seconds) and the threads (the resumes here run with another count, not adapted).
nlohmann::json without_run_environment(nlohmann::json j) {
  if (j.is_object()) {
    nlohmann::json out = nlohmann::json::object();
    for (auto it = j.begin(); it != j.end(); ++it)
      if (it.key().find("second") == std::string::npos && it.key() != "threads" && it.key() != "adapt_threads")
        out[it.key()] = without_run_environment(it.value());
    return out;
  }
  if (j.is_array())
    for (auto& v : j) v = without_run_environment(v);
  return j;
}

// Every file of `expected` (a folder, with its subfolders) but the checkpoint is in `actual`
// with the same bytes.
void expect_same_results(const fs::path& expected, const fs::path& actual) {
  std::set<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(expected))
    if (e.is_regular_file()) names.insert(fs::relative(e.path(), expected).string());
  EXPECT_GT(names.size(), 2u);
  for (const std::string& name : names) {
    if (name == "checkpoint.bin") continue;
    ASSERT_TRUE(fs::exists(actual / name)) << name;
    if (fs::path(name).filename() == "report.json") {
      EXPECT_EQ(without_run_environment(nlohmann::json::parse(read_bytes(expected / name))),
                without_run_environment(nlohmann::json::parse(read_bytes(actual / name))));
      continue;
    }
    EXPECT_TRUE(read_bytes(expected / name) == read_bytes(actual / name)) << name << " differs";
  }
}

// Runs `command IN ARGS --out DIR` straight, then again killed after `first` checkpoints,
// resumed and killed after `second` more, resumed to the end; compares the two folders. The
// runs use the same folder name (outputs may name it).
void expect_resumed_equals_straight(const TempDir& dir, const std::string& command, const std::string& args, int first,
                                    int second, bool plots = true, int resume_threads = 2) {
  const std::string out = dir.file("run");
  const std::string no_plots = plots ? " --no-plots" : "";  // a command that makes plots
  const std::string run_args = command + " " + args + " --checkpoint-seconds 1e-9 --quiet" + no_plots + " --out " + out;
  const auto straight = run_packlab(run_args);
  ASSERT_EQ(straight.exit_code, 0) << straight.output;
  fs::rename(out, dir.file("straight"));
  const auto killed = run_killed(run_args, first);
  ASSERT_EQ(killed.exit_code, 128 + 9) << "not killed at checkpoint " << first << ": " << killed.output;
  const std::string resume = command + " --resume " + out + " --quiet" + no_plots;
  const auto killed_again = run_killed(resume, second);
  ASSERT_EQ(killed_again.exit_code, 128 + 9) << killed_again.output;
  // Neither the thread count nor its adaptation changes the result of the DEM engine.
  const auto resumed = run_packlab(resume + " --threads " + std::to_string(resume_threads) + " --adapt-threads=false");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  expect_same_results(dir.path() / "straight", out);
}

std::string bonded_lattice(const TempDir& dir, const std::string& lattice_args, const std::string& bond_args) {
  const auto g = run_packlab("generate lattice " + lattice_args + " --quiet --out " + dir.file("lattice.xyz"));
  EXPECT_EQ(g.exit_code, 0) << g.output;
  const auto b = run_packlab("bond " + dir.file("lattice.xyz") + " " + bond_args + " --out " + dir.file("model.vtu"));
  EXPECT_EQ(b.exit_code, 0) << b.output;
  return dir.file("model.vtu");
}

// The compression tests' specimen: a simple cubic column of breakable silica bonds, 200 curve
// points over 3 % strain.
std::string compression_column(const TempDir& dir) {
  return bonded_lattice(dir, "--type sc --cells 3 3 6 --radius 7.5e-9", "--model elastic --cutoff-ratio 1.75") +
         " --bond-youngs-modulus 6.53e9 --bond-poisson-ratio 0.17 --bond-strength 94.3e6"
         " --bond-compressive-breakage --strain-rate 4e6 --max-strain 0.03 --samples 200 --threads 1";
}

}  // namespace

TEST(ResumeMechanicsCli, TestCompressKilledTwiceAndResumedEqualsUninterruptedRun) {
  TempDir dir("resume-compress");
  expect_resumed_equals_straight(
      dir, "test compress",
      compression_column(dir) + " --snapshot-strains 0.005,0.02 --snapshot-stresses 100e6,400e6,300e6,1e9", 60, 70);
  // 200 curve points, one checkpoint each, kills after the 60th and 70 more: 100 MPa is reached
  // near point 29, 300 near 88 and 400 near 150 (strains 0.0044, 0.0132, 0.0224 of 0.03), so
  // before, between and after the kills; 1 GPa never: five strain and stress snapshots in the
  // order of the loading.
  const auto report = nlohmann::json::parse(read_bytes(dir.path() / "straight" / "report.json"));
  ASSERT_EQ(report["snapshots"].size(), 5u) << report["snapshots"].dump();
  EXPECT_EQ(report["snapshots"][0].value("requested_stress", 0.0), 100e6);
  EXPECT_EQ(report["snapshots"][1].value("requested_strain", 0.0), 0.005);
  EXPECT_EQ(report["snapshots"][2].value("requested_stress", 0.0), 300e6);
  EXPECT_EQ(report["snapshots"][3].value("requested_strain", 0.0), 0.02);
  EXPECT_EQ(report["snapshots"][4].value("requested_stress", 0.0), 400e6);
  EXPECT_GT(report["snapshots"][2]["strain"].get<double>(), 60.0 / 200 * 0.03);   // after the first kill
  EXPECT_GT(report["snapshots"][4]["strain"].get<double>(), 130.0 / 200 * 0.03);  // after the second
}

// The adaptive rate (--elastic-speedup): killed while the plate still moves fast (point 60 of
// 200) and again after it slowed down at the first break (strain 0.0144, near point 96), resumed
// to the end, the run equals the uninterrupted one bit for bit.
TEST(ResumeMechanicsCli, AdaptiveRateCompressKilledInBothPhasesAndResumedEqualsUninterruptedRun) {
  TempDir dir("resume-compress-adaptive");
  expect_resumed_equals_straight(dir, "test compress", compression_column(dir) + " --elastic-speedup 4", 60, 70);
  const auto report = nlohmann::json::parse(read_bytes(dir.path() / "straight" / "report.json"));
  const double switch_strain = report["adaptive_rate"]["switch_strain"].get<double>();
  EXPECT_GT(switch_strain, 60.0 / 200 * 0.03);   // after the first kill
  EXPECT_LT(switch_strain, 130.0 / 200 * 0.03);  // before the second
  EXPECT_GT(report["adaptive_rate"]["rolled_back_steps"].get<long>(), 0);
}

TEST(ResumeMechanicsCli, TestShearKilledTwiceAndResumedEqualsUninterruptedRun) {
  TempDir dir("resume-shear");
  const std::string model =
      bonded_lattice(dir, "--type sc --cells 4 4 4 --radius 0.25e-6", "--model contact --eps 0.01");
  // Checkpoints: 1 after the relaxation, 2 after z:x, 3 after z:y, then the end.
  expect_resumed_equals_straight(dir, "test shear",
                                 model +
                                     " --stiffness-rule contact --normal-stiffness 100 --shear-stiffness 10"
                                     " --cycles 2 --steps-per-cycle 2000 --regions 1 --orientations z --threads 1",
                                 1, 1);
}

TEST(ResumeMechanicsCli, RelaxKilledTwiceAndResumedEqualsUninterruptedRun) {
  TempDir dir("resume-relax");
  const auto g = run_packlab("generate random --particles 300 --radius 1e-6 --phi 0.6 --seed 2 --quiet --out " +
                             dir.file("start.xyz"));
  ASSERT_EQ(g.exit_code, 0) << g.output;
  const std::string args = dir.file("start.xyz") + " " + dir.file("out/relaxed.vtu") +
                           " --normal-stiffness 1000 --shear-stiffness 10 --friction 0.1 --density 3690"
                           " --stiffness-rule contact --steps 3000 --tolerance 0 --check-interval 50 --threads 1"
                           " --log " +
                           dir.file("out/relax.csv") + " --checkpoint-seconds 1e-9 --quiet --no-plots --checkpoint ";
  fs::create_directories(dir.path() / "out");
  const auto straight = run_packlab("relax " + args + dir.file("straight-checkpoint"));
  ASSERT_EQ(straight.exit_code, 0) << straight.output;
  fs::rename(dir.path() / "out", dir.path() / "straight");
  fs::create_directories(dir.path() / "out");
  const auto killed = run_killed("relax " + args + dir.file("checkpoint"), 17);
  ASSERT_EQ(killed.exit_code, 128 + 9) << killed.output;
  EXPECT_FALSE(fs::exists(dir.file("out/relaxed.vtu")));
  const auto killed_again = run_killed("relax --resume " + dir.file("checkpoint") + " --quiet --no-plots", 11);
  ASSERT_EQ(killed_again.exit_code, 128 + 9) << killed_again.output;
  const auto resumed = run_packlab("relax --resume " + dir.file("checkpoint") + " --threads 2 --quiet --no-plots");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  for (const char* f : {"relaxed.vtu", "relax.csv"})
    EXPECT_TRUE(read_bytes(dir.path() / "straight" / f) == read_bytes(dir.path() / "out" / f)) << f << " differs";

  // An output file or a log given with --resume, a damaged checkpoint: exit code 2.
  const auto with_out = run_packlab("relax --resume " + dir.file("checkpoint") + " " + dir.file("x.vtu"));
  EXPECT_EQ(with_out.exit_code, 2) << with_out.output;
  EXPECT_NE(with_out.output.find("cannot be combined with --resume"), std::string::npos) << with_out.output;
  const fs::path checkpoint = dir.path() / "checkpoint" / "checkpoint.bin";
  std::string bytes = read_bytes(checkpoint);
  ASSERT_GT(bytes.size(), 1000u);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x10);
  std::ofstream(checkpoint, std::ios::binary) << bytes;
  const auto damaged = run_packlab("relax --resume " + dir.file("checkpoint") + " --quiet");
  EXPECT_EQ(damaged.exit_code, 2) << damaged.output;
  EXPECT_NE(damaged.output.find("checkpoint.bin"), std::string::npos) << damaged.output;
}

TEST(ResumeMechanicsCli, CalibrateCompressKilledTwiceAndResumedEqualsUninterruptedRun) {
  // Seven simulations of ~200 checkpoints each (one per curve point, --checkpoint-seconds 1e-9)
  // and one after each: killed within the second simulation, then within the fourth; the
  // resumed runs replay the finished simulations and go on with the running one from its state.
  TempDir dir("resume-calibrate-compress");
  const std::string model =
      bonded_lattice(dir, "--type sc --cells 3 3 6 --radius 7.5e-9", "--model elastic --cutoff-ratio 1.75");
  expect_resumed_equals_straight(dir, "calibrate compress",
                                 model +
                                     " --bond-youngs-modulus 6.53e9 --bond-poisson-ratio 0.17 --bond-strength 94.3e6"
                                     " --bond-compressive-breakage --strain-rate 4e6 --max-strain 0.03 --samples 200"
                                     " --target-youngs-modulus 25e9 --target-strength 540e6 --threads 1",
                                 250, 500);
  const auto csv = read_bytes(dir.path() / "run" / "calibration.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 8) << csv;  // a header and seven simulations
}

TEST(ResumeMechanicsCli, CalibrateShearKilledTwiceAndResumedEqualsUninterruptedRun) {
  // Three simulations (start, finite difference, Newton step: G' is linear in k_n), two
  // orientations each with a checkpoint after each orientation and after each simulation.
  TempDir dir("resume-calibrate-shear");
  const std::string model =
      bonded_lattice(dir, "--type sc --cells 4 4 4 --radius 0.25e-6", "--model contact --eps 0.01");
  expect_resumed_equals_straight(dir, "calibrate shear",
                                 model +
                                     " --target-storage-modulus 2e7 --stiffness-rule contact --normal-stiffness 100"
                                     " --shear-stiffness 10 --cycles 1 --steps-per-cycle 2000 --regions 1"
                                     " --orientations z --threads 1",
                                 2, 3, false);
}

TEST(ResumeMechanicsCli, DamagedCompressionCheckpointIsRefused) {
  TempDir dir("resume-compress-bad");
  const std::string model =
      bonded_lattice(dir, "--type sc --cells 3 3 6 --radius 7.5e-9", "--model elastic --cutoff-ratio 1.75");
  const auto r = run_packlab("test compress " + model +
                             " --strain-rate 4e6 --max-strain 0.005 --quiet --no-plots --out " + dir.file("c"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const fs::path checkpoint = dir.path() / "c" / "checkpoint.bin";
  const std::string bytes = read_bytes(checkpoint);
  ASSERT_GT(bytes.size(), 1000u);
  for (std::size_t k : {std::size_t{5}, bytes.size() / 3, bytes.size() - 2}) {
    std::string damaged = bytes;
    damaged[k] = static_cast<char>(damaged[k] ^ 0x01);
    std::ofstream(checkpoint, std::ios::binary) << damaged;
    const auto resumed = run_packlab("test compress --resume " + dir.file("c") + " --quiet --no-plots");
    EXPECT_EQ(resumed.exit_code, 2) << "byte " << k << ": " << resumed.output;
    EXPECT_NE(resumed.output.find("checkpoint.bin"), std::string::npos) << resumed.output;
  }
}

TEST(ResumeMechanicsCli, StaticCompressionKilledTwiceAndResumedEqualsUninterruptedRun) {
  TempDir dir("resume-compress-static");
  // A random packing (a lattice's bonds break in large ties, a few solves in all): 300 spheres.
  const auto fba = run_packlab(
      "generate fba --particles 300 --diameter 15e-9 --porosity 0.45 --periodic xy --quiet "
      "--no-plots --out " +
      dir.file("fba"));
  ASSERT_EQ(fba.exit_code, 0) << fba.output;
  const auto bond = run_packlab("bond " + dir.file("fba") + "/packing.vtu --model elastic --cutoff-ratio 1.1 --out " +
                                dir.file("model.vtu"));
  ASSERT_EQ(bond.exit_code, 0) << bond.output;
  const std::string model = dir.file("model.vtu");
  // A fresh factorization every 4 breaks, a checkpoint at each (--checkpoint-seconds 1e-9), a
  // check every 3rd re-solve: killed after the 3rd checkpoint and again after 2 more. Resumed at
  // one thread, as it ran: CHOLMOD's kernels round differently at two (docs/static-solver.md).
  expect_resumed_equals_straight(dir, "test compress",
                                 model +
                                     " --bond-youngs-modulus 6.53e9 --bond-poisson-ratio 0.17 --bond-strength 94.3e6"
                                     " --solver static --max-strain 0.2 --stop-drop 0.5 --checkpoint-breaks 4"
                                     " --check-interval 3 --snapshot-strains 0.005,0.04"
                                     " --snapshot-stresses 100e6,160e6,170e6 --threads 1",
                                 3, 2, true, 1);
  const auto straight = nlohmann::json::parse(read_bytes(dir.path() / "straight" / "report.json"));
  // Enough breaks for five checkpoints, and the factorizations they make.
  EXPECT_GE(straight["broken_bonds"].get<long>(), 20) << straight.dump();
  // 100 and 160 MPa on the first two branches (the envelope peaks near 163 MPa at the second
  // break, strain 0.047), 170 MPa never: in the order of the strains 0.005, 100 MPa (0.028 on
  // the first branch), 0.04, 160 MPa (0.046 on the second); restored on resume.
  ASSERT_EQ(straight["snapshots"].size(), 4u) << straight["snapshots"].dump();
  EXPECT_EQ(straight["snapshots"][0].value("requested_strain", 0.0), 0.005);
  EXPECT_EQ(straight["snapshots"][1].value("requested_stress", 0.0), 100e6);
  EXPECT_EQ(straight["snapshots"][2].value("requested_strain", 0.0), 0.04);
  EXPECT_EQ(straight["snapshots"][3].value("requested_stress", 0.0), 160e6);
  const auto help = run_packlab("test compress --help");
  EXPECT_NE(help.output.find("--solver static at the first of its fresh factorizations"), std::string::npos)
      << help.output;
}
