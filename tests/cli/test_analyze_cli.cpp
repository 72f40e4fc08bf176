// `packlab analyze` end to end: lattices give exact coordination in report.json, tables have
// the documented columns, several files are realizations, the same seed gives the same
// report, a user-given box and periodicity reach the reader, bad input exits with code 2.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>

#include "packlab/generate/lattice.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab {
namespace {

namespace fs = std::filesystem;

class AnalyzeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) /
           (std::string("packlab_analyze_") + info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // Runs packlab with `args`; returns the exit code, stderr in `err`.
  int run(const std::string& args, std::string* err = nullptr) const {
    const fs::path err_file = dir_ / "stderr.txt";
    const std::string cmd = std::string(PACKLAB_BINARY) + " " + args + " > /dev/null 2> " + err_file.string();
    const int status = std::system(cmd.c_str());
    if (err) {
      std::ifstream in(err_file);
      std::stringstream s;
      s << in.rdbuf();
      *err = s.str();
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  nlohmann::json report(const std::string& out) const {
    std::ifstream in(dir_ / out / "report.json");
    return nlohmann::json::parse(in);
  }

  std::string first_data_line(const fs::path& csv) const {
    std::ifstream in(csv);
    std::string line;
    while (std::getline(in, line))
      if (!line.empty() && line[0] != '#') return line;
    return "";
  }

  fs::path lattice_file(const std::string& name, generate::LatticeType type) const {
    generate::LatticeParams p;
    p.type = type;
    p.cells = {3, 3, 3};
    p.radius = 0.5;
    const fs::path path = dir_ / name;
    io::write_packing(generate::make_lattice(p), path);
    return path;
  }

  fs::path dir_;
};

TEST_F(AnalyzeCli, FccLatticeReportHasExactCoordinationAndTheDocumentedKeys) {
  const fs::path fcc = lattice_file("fcc.xyz", generate::LatticeType::fcc);
  ASSERT_EQ(run("analyze " + fcc.string() + " --out " + (dir_ / "out").string() + " --no-plots --quiet"), 0);
  const auto r = report("out");
  EXPECT_EQ(r["command"], "analyze");
  EXPECT_DOUBLE_EQ(r["mean_coordination"].get<double>(), 12.0);
  EXPECT_EQ(r["rattlers"].get<long>(), 0);
  EXPECT_NEAR(r["volume_fraction"].get<double>(), std::numbers::pi / (3 * std::sqrt(2.0)), 1e-12);
  for (const char* key : {"a", "b", "a_err", "b_err", "r2"}) EXPECT_TRUE(r["doh"].contains(key)) << key;
  EXPECT_GT(r["doh"]["a"].get<double>(), 0.0);
  EXPECT_NEAR(r["fabric"]["anisotropy"].get<double>(), 0.0, 1e-12);
  EXPECT_EQ(r["pore_size"]["points"].get<long>(), r["parameters"]["points_used_per_file"].get<long>());
  EXPECT_TRUE(r.contains("seconds"));
  EXPECT_EQ(r["seed"].get<long>(), 1);
  EXPECT_EQ(first_data_line(dir_ / "out" / "pore_size.csv"), "r,probability,std_error,band_low,band_high,fit");
  EXPECT_EQ(first_data_line(dir_ / "out" / "coordination.csv"), "contacts,particles,fraction");
  EXPECT_TRUE(fs::exists(dir_ / "out" / "contact_normals.csv"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "coordination_types.csv"));
  // --what all includes the RDF (analyze/rdf.hpp, the tables of `packlab analyze rdf`).
  EXPECT_TRUE(r.contains("rdf"));
  EXPECT_EQ(first_data_line(dir_ / "out" / "rdf.csv").rfind("r,R,", 0), 0u);
  // FCC: the largest distance to a surface is at the octahedral hole, a/2 - R = (sqrt 2 - 1) R.
  EXPECT_LE(r["pore_size"]["largest_distance_m"].get<double>(), (std::sqrt(2.0) - 1.0) * 0.5 + 1e-12);
}

TEST_F(AnalyzeCli, SeveralFilesAreRealizationsAndTheSeedFixesTheResult) {
  const fs::path sc = lattice_file("sc.txt", generate::LatticeType::sc);
  const fs::path bcc = lattice_file("bcc.txt", generate::LatticeType::bcc);
  const std::string files = sc.string() + " " + bcc.string();
  ASSERT_EQ(run("analyze " + files + " --out " + (dir_ / "a").string() +
                " --what cn,pores --points 5000 --no-plots --quiet --seed 9"),
            0);
  ASSERT_EQ(run("analyze " + files + " --out " + (dir_ / "b").string() +
                " --what cn,pores --points 5000 --no-plots --quiet --seed 9 --threads 1"),
            0);
  auto a = report("a"), b = report("b");
  EXPECT_EQ(a["realizations"].get<int>(), 2);
  EXPECT_DOUBLE_EQ(a["mean_coordination"].get<double>(), (27.0 * 6 + 54.0 * 8) / 81.0);
  EXPECT_EQ(a["per_file"][0]["mean_coordination"].get<double>(), 6.0);
  EXPECT_EQ(a["per_file"][1]["mean_coordination"].get<double>(), 8.0);
  EXPECT_EQ(a["pore_size"]["points"].get<long>(), 10000);
  EXPECT_FALSE(a.contains("doh"));
  EXPECT_FALSE(a.contains("fabric"));
  EXPECT_FALSE(a.contains("rdf"));
  EXPECT_EQ(a["pore_size"], b["pore_size"]);  // same seed, different thread count
}

TEST_F(AnalyzeCli, UserBoxAndPeriodicityReachTheReader) {
  // An SC lattice written without its box: with the right periodic box every particle has 6
  // contacts; with the bounding box (open) the surface particles have fewer.
  generate::LatticeParams p;
  p.type = generate::LatticeType::sc;
  p.cells = {3, 3, 3};
  p.radius = 0.5;
  const Packing lattice = generate::make_lattice(p);
  const fs::path file = dir_ / "nobox.txt";
  {
    std::ofstream out(file);
    out.precision(17);
    for (std::size_t i = 0; i < lattice.size(); ++i)
      out << lattice.position[i].x << ' ' << lattice.position[i].y << ' ' << lattice.position[i].z << ' '
          << lattice.radius[i] << '\n';
  }
  ASSERT_EQ(run("analyze " + file.string() + " --out " + (dir_ / "open").string() + " --what cn --no-plots --quiet"),
            0);
  EXPECT_LT(report("open")["mean_coordination"].get<double>(), 6.0);
  ASSERT_EQ(run("analyze " + file.string() + " --out " + (dir_ / "pbc").string() +
                " --what cn --box 3 3 3 --periodic 1 1 1 --no-plots --quiet"),
            0);
  EXPECT_DOUBLE_EQ(report("pbc")["mean_coordination"].get<double>(), 6.0);
}

TEST_F(AnalyzeCli, BadInputExitsWithCodeTwo) {
  const fs::path fcc = lattice_file("fcc.xyz", generate::LatticeType::fcc);
  const std::string out = " --out " + (dir_ / "out").string() + " --no-plots --quiet";
  std::string err;
  EXPECT_EQ(run("analyze " + fcc.string() + out + " --what shape", &err), 2);
  EXPECT_NE(err.find("what = shape"), std::string::npos) << err;
  EXPECT_EQ(run("analyze " + fcc.string() + out + " --contact-eps -1", &err), 2);
  EXPECT_NE(err.find("contact_eps"), std::string::npos) << err;
  EXPECT_EQ(run("analyze " + fcc.string() + out + " --pore-definition all_points --what doh", &err), 2);
  EXPECT_EQ(run("analyze " + fcc.string() + " --no-plots", &err), 2);
  EXPECT_NE(err.find("--out"), std::string::npos) << err;
  EXPECT_EQ(run("analyze " + (dir_ / "missing.txt").string() + out, &err), 2);
}

}  // namespace
}  // namespace packlab
