// packlab test compress / calibrate compress as a user meets them: a lattice bonded with
// `packlab bond --model elastic`, report.json with the SI results, the files of every curve, and
// bad input as one line with exit code 2.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using packlab::test::run_packlab;
using packlab::test::TempDir;

namespace {

// A 3 x 3 x 6 simple cubic lattice of 15 nm particles with elastic bonds.
std::string bonded_lattice(const TempDir& dir) {
  const std::string lattice = dir.file("sc.xyz"), model = dir.file("sc.vtu");
  EXPECT_EQ(run_packlab("generate lattice --type sc --cells 3 3 6 --radius 7.5e-9 --quiet --out " + lattice).exit_code, 0);
  const auto b = run_packlab("bond " + lattice + " --model elastic --cutoff-ratio 1.75 --out " + model);
  EXPECT_EQ(b.exit_code, 0) << b.output;
  return model;
}

}  // namespace

TEST(UniaxialCompressionCli, LatticeReportAndCurves) {
  TempDir dir("compress-cli");
  const std::string model = bonded_lattice(dir);
  const std::string out = dir.file("run");
  const auto r = run_packlab("test compress " + model + " --out " + out +
                             " --bond-youngs-modulus 6.53e9 --bond-poisson-ratio 0.17 --bond-strength 94.3e6"
                             " --bond-compressive-breakage --strain-rate 4e6 --max-strain 0.03 --snapshot-strains 0.005,0.01"
                             " --threads 1 --no-plots --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_GT(report.at("youngs_modulus").get<double>(), 1e9);
  EXPECT_LT(report.at("youngs_modulus").get<double>(), 1e11);
  EXPECT_GT(report.at("strength").get<double>(), 1e6);
  EXPECT_GT(report.at("broken_bonds").get<long>(), 0);  // axial bonds fail in compression at 94.3 MPa / 6.53 GPa
  EXPECT_EQ(report.at("fixed_particles").get<long>(), 18);  // two bottom levels of 9
  EXPECT_EQ(report.at("snapshots").size(), 2u);
  for (const char* f : {"curve.csv", "bond_strain.csv", "particle_stress.csv", "broken_bonds.csv", "broken_bonds.vtu",
                        "model.vtu"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
}

TEST(UniaxialCompressionCli, ConfigFileAndFlagsOverride) {
  TempDir dir("compress-cli-config");
  const std::string model = bonded_lattice(dir);
  {
    std::ofstream cfg(dir.file("c.toml"));
    cfg << "max_strain = 0.002\nstrain_rate = 4e6\n[silica]\nyoungs_modulus = 1e9\nstrength = 1e30\n";
  }
  const auto r = run_packlab("test compress " + model + " --config " + dir.file("c.toml") + " --out " + dir.file("a") +
                             " --bond-youngs-modulus 2e9 --threads 1 --no-plots --no-vtu --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(dir.file("a") + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const nlohmann::json& parameters = report.at("parameters");
  EXPECT_EQ(parameters.at("silica").at("youngs_modulus_Pa").get<double>(), 2e9);  // the flag wins
  EXPECT_EQ(parameters.at("max_strain").get<double>(), 0.002);                   // from the file
  EXPECT_EQ(report.at("max_strain").get<double>(), 0.002);
  EXPECT_EQ(report.at("broken_bonds").get<long>(), 0);
}

TEST(UniaxialCompressionCli, BadInputIsOneLineAndExitCode2) {
  TempDir dir("compress-cli-bad");
  const std::string model = bonded_lattice(dir);
  for (const std::string args : {" --strain-rate -1", " --sides closed", " --max-strain 2", " --bond-poisson-ratio 0.7"}) {
    const auto r = run_packlab("test compress " + model + " --out " + dir.file("x") + args + " --quiet");
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
  const auto c = run_packlab("calibrate compress " + model + " --out " + dir.file("y") + " --quiet");
  EXPECT_EQ(c.exit_code, 2) << c.output;
  EXPECT_NE(c.output.find("target-youngs-modulus"), std::string::npos) << c.output;
}
