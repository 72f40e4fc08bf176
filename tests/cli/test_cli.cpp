// The command line as a user meets it: `info` on an FCC lattice,
// every subcommand's --help, and each error path: one line, exit code 2, nothing written.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using packlab::test::run_packlab;
using packlab::test::TempDir;

namespace {

int count_lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// Files in the folder (temporaries included): a failed run must leave none behind.
int files_in(const std::filesystem::path& dir) {
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) n += e.is_regular_file();
  return n;
}

}  // namespace

TEST(Cli, VersionAndHelpOfEverySubcommand) {
  const auto v = run_packlab("--version");
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_NE(v.output.find("packlab "), std::string::npos);
  for (const char* sub : {"generate lattice", "generate random", "info", "convert", "relax"}) {
    const auto h = run_packlab(std::string(sub) + " --help");
    EXPECT_EQ(h.exit_code, 0) << sub;
    EXPECT_NE(h.output.find("Usage"), std::string::npos) << sub << ": " << h.output;
  }
}

TEST(Cli, FccLatticeOfTouchingSpheresReportsItsVolumeFractionAndTwelveContacts) {
  TempDir dir("fcc");
  const auto g = run_packlab("generate lattice --type fcc --cells 4 4 4 --radius 0.25e-6 --out " + dir.file("fcc.xyz"));
  ASSERT_EQ(g.exit_code, 0) << g.output;
  const auto info = run_packlab("info " + dir.file("fcc.xyz") + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.output;
  const auto j = nlohmann::json::parse(info.output);
  EXPECT_EQ(j["particles"], 256);
  EXPECT_NEAR(j["volume_fraction"].get<double>(), 0.7405, 5e-5);
  EXPECT_DOUBLE_EQ(j["mean_coordination"].get<double>(), 12.0);
  EXPECT_EQ(j["periodic"], nlohmann::json::array({true, true, true}));
  const double edge = 4 * std::sqrt(2.0) * 0.5e-6;
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(j["box"][a].get<double>(), edge, 1e-12 * edge);
  const auto text = run_packlab("info " + dir.file("fcc.xyz"));
  EXPECT_NE(text.output.find("0.740480"), std::string::npos) << text.output;
}

TEST(Cli, ConvertKeepsThePackingAcrossFormats) {
  TempDir dir("convert");
  ASSERT_EQ(run_packlab("generate random --particles 300 --radius 0.5 --phi 0.3 --no-overlap --seed 9 --out " +
                        dir.file("a.xyz"))
                .exit_code,
            0);
  for (const char* ext : {"vtu", "data", "csv", "txt"}) {
    const std::string to = dir.file(std::string("b.") + ext);
    ASSERT_EQ(run_packlab("convert " + dir.file("a.xyz") + " " + to).exit_code, 0) << ext;
    const auto a = nlohmann::json::parse(run_packlab("info --json " + dir.file("a.xyz")).output);
    const auto b = nlohmann::json::parse(run_packlab("info --json " + to).output);
    EXPECT_EQ(a["particles"], b["particles"]) << ext;
    EXPECT_EQ(a["volume_fraction"], b["volume_fraction"]) << ext;
    EXPECT_EQ(a["box"], b["box"]) << ext;
  }
}

TEST(Cli, RelaxWritesARelaxedPackingAndSaysWhyItStopped) {
  TempDir dir("relax");
  ASSERT_EQ(run_packlab("generate random --particles 400 --radius 0.5 --phi 0.68 --seed 2 --out " + dir.file("in.xyz"))
                .exit_code,
            0);
  const auto r = run_packlab("relax " + dir.file("in.xyz") + " " + dir.file("out.vtu") +
                             " --normal-stiffness 1000 --tolerance 1e-2 --steps 50000 --quiet");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir.file("out.vtu")));
  const auto exact = run_packlab("relax " + dir.file("in.xyz") + " " + dir.file("exact.xyz") +
                                 " --tolerance 0 --steps 300 --log " + dir.file("log.csv"));
  EXPECT_EQ(exact.exit_code, 0) << exact.output;
  EXPECT_NE(exact.output.find("step limit: 300 steps"), std::string::npos) << exact.output;
  std::ifstream log(dir.file("log.csv"));
  std::string header;
  std::getline(log, header);
  EXPECT_EQ(header.rfind("step,time,kinetic_energy,strain_energy,unbalanced_force_ratio", 0), 0u);
}

TEST(Cli, BadInputGivesOneLineAndExitCodeTwoAndWritesNothing) {
  TempDir dir("errors");
  {
    std::ofstream bad(dir.file("bad.txt"));
    bad << "# box 10 10 10\n1 2 3 0.5\n4 5 six 0.5\n";
    std::ofstream negative(dir.file("negative.txt"));
    negative << "# box 10 10 10\n1 2 3 0.5\n4 5 6 -0.5\n";
  }
  const std::string out = dir.file("out.xyz");
  struct Case {
    const char* what;
    std::string args;
    const char* mentions;
  };
  const Case cases[] = {
      {"missing file", "info " + dir.file("nope.xyz"), "nope.xyz"},
      {"malformed number", "convert " + dir.file("bad.txt") + " " + out, "bad.txt"},
      {"negative radius in a file", "relax " + dir.file("negative.txt") + " " + out, "radius"},
      {"unknown option", "info " + dir.file("bad.txt") + " --frobnicate", "frobnicate"},
      {"unknown subcommand", "levitate", "levitate"},
      {"negative radius", "generate lattice --radius -1 --out " + out, "radius"},
      {"unknown lattice", "generate lattice --type hcp --out " + out, "hcp"},
      {"impossible volume fraction", "generate random --phi 1.5 --out " + out, "1.5"},
      {"RSA beyond jamming", "generate random --phi 0.5 --no-overlap --out " + out, "0.5"},
      {"unknown output format", "generate lattice --out " + dir.file("x.pdf"), "pdf"},
  };
  for (const auto& c : cases) {
    const auto r = run_packlab(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.what << ": " << r.output;
    EXPECT_EQ(count_lines(r.output), 1) << c.what << ": " << r.output;
    EXPECT_NE(r.output.find(c.mentions), std::string::npos) << c.what << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.what;
  }
  // Parameter checks of relax on a valid packing: stiffness, damping.
  ASSERT_EQ(run_packlab("generate lattice --cells 2 2 2 --out " + dir.file("fcc.xyz")).exit_code, 0);
  for (const char* bad : {"--normal-stiffness -5", "--damping 1.2", "--shear-stiffness -1", "--time-step -1"}) {
    const auto r = run_packlab("relax " + dir.file("fcc.xyz") + " " + out + " " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.output;
    EXPECT_EQ(count_lines(r.output), 1) << bad << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << bad;
  }
  // Only the two inputs and fcc.xyz: no temporary or partial file left behind.
  EXPECT_EQ(files_in(dir.path()), 3);
}

TEST(Cli, UnwritableOutputFolderIsAnInputError) {
  TempDir dir("unwritable");
  const auto r = run_packlab("generate lattice --out " + dir.file("no/such/folder/x.xyz"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(count_lines(r.output), 1) << r.output;
}
