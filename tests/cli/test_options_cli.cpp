// Every command whose options are one option set (io/options.hpp) takes each key of its config
// file as a flag named after it and nothing else: `packlab CMD --help` lists exactly the keys of
// `packlab config-keys` (with `-` for `.` and `_`, plus the aliases the reference names) and the
// flags that steer the run. python/tests/test_options.py checks the Python keywords the same way.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "cli_runner.hpp"

using packlab::test::run_packlab;

namespace {

const char* const ported[] = {"generate lattice",
                              "generate random",
                              "generate vem",
                              "generate ls",
                              "generate scrm",
                              "generate fba",
                              "build opal",
                              "shake",
                              "bond",
                              "relax",
                              "test shear",
                              "calibrate shear",
                              "test compress",
                              "calibrate compress",
                              "analyze",
                              "analyze rdf"};

// Flags that steer the run rather than set an option.
const std::set<std::string> run_control{"--help",   "--config", "--out",   "--resume", "--no-plots",
                                        "--no-vtu", "--check",  "--quiet", "--log",    "--checkpoint"};

std::string flag_of(std::string key) {
  for (char& c : key)
    if (c == '.' || c == '_') c = '-';
  return "--" + key;
}

// The flags the reference table of `command` declares: one per key, one per alias.
std::set<std::string> declared_flags(const std::string& reference, const std::string& command) {
  const std::string heading = "## `packlab " + command + "`";
  const auto start = reference.find(heading);
  EXPECT_NE(start, std::string::npos) << command;
  const auto end = reference.find("\n## ", start + 1);
  std::istringstream section(reference.substr(start, end == std::string::npos ? std::string::npos : end - start));
  std::set<std::string> flags;
  const std::regex row(R"(^\| `([^`]+)` \|.*)"), alias(R"(\(also ([^)]*)\))"), name(R"(--[a-z0-9-]+)");
  for (std::string line; std::getline(section, line);) {
    std::smatch m;
    if (!std::regex_match(line, m, row)) continue;
    flags.insert(flag_of(m[1]));
    std::smatch a;
    if (std::regex_search(line, a, alias)) {
      const std::string names = a[1];
      for (auto it = std::sregex_iterator(names.begin(), names.end(), name); it != std::sregex_iterator(); ++it)
        flags.insert(it->str());
    }
  }
  return flags;
}

std::set<std::string> help_flags(const std::string& command) {
  const auto r = run_packlab(command + " --help");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  std::set<std::string> flags;
  std::istringstream in(r.output);
  const std::regex option(R"(^\s+(-[-\w,]+).*)");
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (!std::regex_match(line, m, option)) continue;
    std::stringstream names(m[1]);
    for (std::string n; std::getline(names, n, ',');)
      if (n.rfind("--", 0) == 0 && run_control.count(n) == 0) flags.insert(n);
  }
  return flags;
}

}  // namespace

TEST(OptionSets, EveryPortedCommandsFlagsAreItsConfigKeys) {
  const auto reference = run_packlab("config-keys");
  ASSERT_EQ(reference.exit_code, 0) << reference.output;
  for (const char* command : ported) {
    const auto declared = declared_flags(reference.output, command);
    EXPECT_GT(declared.size(), 2u) << command;
    EXPECT_EQ(help_flags(command), declared) << command;
  }
}

TEST(OptionSets, FlagOverridesTheFileWhichOverridesTheDefault) {
  packlab::test::TempDir dir("option-precedence");
  {
    std::ofstream f(dir.file("vem.toml"));
    f << "structural = 100\nvoids = 50\n";
  }
  const auto r =
      run_packlab("generate vem --check --config " + dir.file("vem.toml") + " --voids 60 --out " + dir.file("o"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("N_S = 100, N_V = 60"), std::string::npos) << r.output;  // file, flag
  EXPECT_NE(r.output.find("Phi_S = 0.4,"), std::string::npos) << r.output;         // default
  const auto bad = run_packlab("generate vem --check --relax-max-steps 1.5 --out " + dir.file("o"));
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--relax-max-steps = 1.5: must be an integer"), std::string::npos) << bad.output;
}
