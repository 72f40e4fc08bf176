// Inputs a new user tries that used to crash, run for minutes before failing, or succeed
// silently: each now stops at once with one line and exit code 2, and leaves no output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_runner.hpp"

using packlab::test::run_packlab;
using packlab::test::TempDir;

namespace {

void expect_refused(const std::string& args, const std::string& key) {
  const auto r = run_packlab(args);
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
  EXPECT_NE(r.output.find(key), std::string::npos) << args << "\n" << r.output;
  EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

}  // namespace

TEST(BadSizes, RefusedWithTheMemoryEstimateBeforeAllocating) {
  TempDir dir("bad-sizes");
  // 4e9 spheres (256 GB) and 1e12 VEM particles: more than any machine this runs on.
  expect_refused("generate lattice --type fcc --cells 1000,1000,1000 --out " + dir.file("l.xyz"), "GB");
  expect_refused("generate vem --structural 1000000000000 --check --out " + dir.file("v"), "GB");
  EXPECT_FALSE(std::filesystem::exists(dir.file("l.xyz")));
}

TEST(BadOptions, ThreadCountsOutOfRange) {
  TempDir dir("bad-threads");
  ASSERT_EQ(run_packlab("generate lattice --type sc --cells 3,3,3 --out " + dir.file("sc.xyz")).exit_code, 0);
  expect_refused("bond " + dir.file("sc.xyz") + " --threads -1 --out " + dir.file("b.vtu"), "threads");
  expect_refused("relax " + dir.file("sc.xyz") + " " + dir.file("r.xyz") + " --threads 100000", "threads");
  EXPECT_FALSE(std::filesystem::exists(dir.file("b.vtu")));
}

TEST(BadOutputs, CheckedBeforeTheRun) {
  TempDir dir("bad-outputs");
  ASSERT_EQ(run_packlab("generate lattice --type sc --cells 3,3,3 --out " + dir.file("sc.xyz")).exit_code, 0);
  ASSERT_EQ(run_packlab("bond " + dir.file("sc.xyz") + " --out " + dir.file("b.vtu") + " --quiet").exit_code, 0);
  std::ofstream(dir.file("a-file")) << "x";
  // An output folder that is a file, an output file in a folder that does not exist, a log
  // that cannot be written: refused before any step runs.
  expect_refused("test compress " + dir.file("b.vtu") + " --out " + dir.file("a-file") + " --quiet", "a-file");
  expect_refused("relax " + dir.file("sc.xyz") + " " + dir.file("no/such/r.xyz") + " --quiet", "does not exist");
  expect_refused(
      "relax " + dir.file("sc.xyz") + " " + dir.file("r.xyz") + " --log " + dir.file("no/l.csv") + " --quiet",
      "does not exist");
  EXPECT_FALSE(std::filesystem::exists(dir.file("r.xyz")));
}

TEST(Targets, AnLsTargetThatIsNotReachedIsAnError) {
  TempDir dir("ls-target");
  const auto r = run_packlab("generate ls --particles 200 --phi 0.9 --no-plots --quiet --out " + dir.file("ls"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("phi = 0.9: not reached"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir.file("ls/packing.xyz")));  // what was reached, for inspection
}

TEST(BadPackings, TwoParticlesAtOnePointStopTheDemCommands) {
  TempDir dir("coincident");
  ASSERT_EQ(run_packlab("generate lattice --type sc --cells 3,3,3 --out " + dir.file("sc.xyz")).exit_code, 0);
  // The same file with its first particle twice (the count header raised by one).
  std::ifstream in(dir.file("sc.xyz"));
  std::string count, comment, first, rest, line;
  std::getline(in, count);
  std::getline(in, comment);
  std::getline(in, first);
  while (std::getline(in, line)) rest += line + "\n";
  std::ofstream(dir.file("twice.xyz")) << std::stol(count) + 1 << "\n"
                                       << comment << "\n"
                                       << first << "\n"
                                       << first << "\n"
                                       << rest;
  expect_refused("relax " + dir.file("twice.xyz") + " " + dir.file("r.xyz") + " --quiet", "same position");
  EXPECT_FALSE(std::filesystem::exists(dir.file("r.xyz")));
}

TEST(BadPackings, MemoryExhaustedInsideAParallelRegionIsOneMessageAndExitCodeTwo) {
  // 10^5 spheres at one point: each lists every other as a neighbour, and under a 700 MB
  // address-space limit the pair lists run out of memory inside the neighbour search's OpenMP
  // region. That used to abort (std::terminate, exit 134); now the bad_alloc leaves the region
  // (core/parallel_errors.hpp) and main prints its out-of-memory line.
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: an address-space limit stops it, not packlab";
#endif
  TempDir dir("one-point");
  {
    std::ofstream f(dir.file("point.xyz"));
    f << "100000\nLattice=\"1 0 0 0 1 0 0 0 1\" Origin=\"0 0 0\" pbc=\"T T T\" "
         "Properties=species:S:1:pos:R:3:radius:R:1\n";
    for (int k = 0; k < 100000; ++k) f << "T0 0.5 0.5 0.5 0.001\n";
  }
  for (const char* threads : {"1", "2"}) {
    const std::string cmd = std::string("bash -c 'ulimit -v 700000; OMP_NUM_THREADS=") + threads + " exec " +
                            PACKLAB_BINARY + " info " + dir.file("point.xyz") + "' 2>&1";
    FILE* pipe = ::popen(cmd.c_str(), "r");
    std::string output;
    char buffer[4096];
    while (pipe && std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
    const int status = pipe ? ::pclose(pipe) : -1;
    ASSERT_TRUE(WIFEXITED(status)) << output;
    EXPECT_EQ(WEXITSTATUS(status), 2) << threads << " threads: " << output;
    EXPECT_TRUE(output.find("out of memory") != std::string::npos || output.find("coincident") != std::string::npos)
        << output;
    EXPECT_LE(std::count(output.begin(), output.end(), '\n'), 1) << output;
  }
}

TEST(BadOutputs, InputRefusedOnceTheRunStartsLeavesNoEmptyOutputFolder) {
  TempDir dir("no-empty-folder");
  ASSERT_EQ(run_packlab("generate lattice --type sc --cells 3 3 6 --out " + dir.file("sc.xyz")).exit_code, 0);
  std::ofstream(dir.file("bad.xyz")) << "garbage\n";
  // A packing without bonds is refused by the tests only after they started; a bad file among
  // the inputs of analyze only when analyze reaches it.
  expect_refused("test compress " + dir.file("sc.xyz") + " --quiet --out " + dir.file("c"), "no bonds");
  expect_refused("test shear " + dir.file("sc.xyz") + " --quiet --out " + dir.file("s"), "no intact bond");
  expect_refused("analyze " + dir.file("bad.xyz") + " --quiet --out " + dir.file("a"), "garbage");
  expect_refused("analyze rdf " + dir.file("bad.xyz") + " --quiet --out " + dir.file("r"), "garbage");
  for (const char* out : {"c", "s", "a", "r"}) EXPECT_FALSE(std::filesystem::exists(dir.file(out))) << out;
  // A folder that existed before stays.
  std::filesystem::create_directories(dir.file("kept"));
  expect_refused("test compress " + dir.file("sc.xyz") + " --quiet --out " + dir.file("kept"), "no bonds");
  EXPECT_TRUE(std::filesystem::exists(dir.file("kept")));
}
