// packlab bond + packlab test shear + packlab calibrate shear as a user runs them: a bonded
// simple-cubic lattice (closed form G = k_s n / ((2n + 1) d), tests/mechanics/test_shear_test.cpp),
// the report's keys, config file + flag override, and the error paths (exit 2, one line).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using packlab::test::run_packlab;
using packlab::test::TempDir;

namespace {

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

std::string bonded_sc(const TempDir& dir) {
  const auto g = run_packlab("generate lattice --type sc --cells 4 4 4 --radius 0.25e-6 --out " + dir.file("sc.xyz"));
  EXPECT_EQ(g.exit_code, 0) << g.output;
  const auto b = run_packlab("bond " + dir.file("sc.xyz") + " --model contact --eps 0.01 --out " + dir.file("sc.vtu"));
  EXPECT_EQ(b.exit_code, 0) << b.output;
  EXPECT_NE(b.output.find("192 bonds"), std::string::npos) << b.output;
  return dir.file("sc.vtu");
}

// G of the 4-layer simple-cubic network for contact shear stiffness ks [N/m].
double sc_modulus(double ks) { return ks * 4.0 / (9.0 * 0.5e-6); }

}  // namespace

TEST(OscillatoryShearCli, LatticeReportHasTheStorageModulusOfTheClosedFormAndWritesEveryOutput) {
  TempDir dir("shear-cli");
  const std::string model = bonded_sc(dir);
  const auto r = run_packlab("test shear " + model +
                             " --stiffness-rule contact --normal-stiffness 100 --shear-stiffness 10 --cycles 2"
                             " --steps-per-cycle 4000 --regions 1 --orientations z --no-plots --quiet --out " +
                             dir.file("out"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = read_json(dir.file("out/report.json"));
  const double g = j["storage_modulus"]["mean"].get<double>();
  EXPECT_NEAR(g, sc_modulus(10.0), 0.01 * sc_modulus(10.0));
  ASSERT_EQ(j["storage_modulus"]["per_orientation"].size(), 2u);
  EXPECT_EQ(j["storage_modulus"]["per_orientation"][0]["orientation"], "z:x");
  EXPECT_LT(std::abs(j["phase_angle"].get<double>()), 0.01);
  EXPECT_EQ(j["bonds"]["broken_during_loading"], 0);
  for (const char* f : {"stress_strain.csv", "cycles.csv", "relaxed.vtu"})
    EXPECT_TRUE(std::filesystem::exists(dir.file(std::string("out/") + f))) << f;
  // The relaxed model keeps its bonds: it can be tested again.
  const auto info = run_packlab("info " + dir.file("out/relaxed.vtu"));
  EXPECT_EQ(info.exit_code, 0) << info.output;
}

TEST(OscillatoryShearCli, ConfigFileIsReadAndFlagsOverrideIt) {
  TempDir dir("shear-cli-config");
  const std::string model = bonded_sc(dir);
  {
    std::ofstream cfg(dir.file("shear.toml"));
    cfg << "stiffness_rule = \"contact\"\nshear_stiffness = 20.0\ncycles = 1\nsteps_per_cycle = 4000\n"
           "regions = 1\norientations = \"z:x\"\n[output]\nplots = false\n";
  }
  const auto r = run_packlab("test shear " + model + " --config " + dir.file("shear.toml") +
                             " --shear-stiffness 10 --quiet --out " + dir.file("out"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = read_json(dir.file("out/report.json"));
  EXPECT_EQ(j["parameters"]["cycles"], 1);
  EXPECT_DOUBLE_EQ(j["parameters"]["shear_stiffness_N_per_m"].get<double>(), 10.0);
  EXPECT_NEAR(j["storage_modulus"]["mean"].get<double>(), sc_modulus(10.0), 0.01 * sc_modulus(10.0));
}

TEST(OscillatoryShearCli, CalibrateFindsTheShearStiffnessRatioOfTheLattice) {
  // The cubic network's G' is k_s n / ((2n + 1) d) with k_s = k_n / 10: the k_n of a target
  // G' = sc_modulus(15) is 150 N/m.
  TempDir dir("shear-cli-calibrate");
  const std::string model = bonded_sc(dir);
  const auto r = run_packlab("calibrate shear " + model + " --target-storage-modulus " +
                             std::to_string(sc_modulus(15.0)) +
                             " --stiffness-rule contact --cycles 1 --steps-per-cycle 4000 --regions 1"
                             " --orientations z:x --quiet --out " +
                             dir.file("cal"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = read_json(dir.file("cal/report.json"));
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_NEAR(j["normal_stiffness"].get<double>(), 150.0, 0.01 * 150.0);
}

TEST(OscillatoryShearCli, BadInputStopsWithOneLineAndExitCode2) {
  TempDir dir("shear-cli-errors");
  const std::string model = bonded_sc(dir);
  struct Case {
    std::string args, key;
  };
  const std::vector<Case> cases = {
      {"test shear " + model + " --orientations w --out " + dir.file("o1"), "orientations"},
      {"test shear " + model + " --amplitude -1 --out " + dir.file("o2"), "amplitude"},
      {"test shear " + model + " --steps-per-cycle 1001 --out " + dir.file("o3"), "steps_per_cycle"},
      {"test shear " + dir.file("sc.xyz") + " --out " + dir.file("o4"), "no intact bond"},
  };
  for (const auto& c : cases) {
    const auto r = run_packlab(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find("packlab: error:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.key), std::string::npos) << r.output;
  }
}
