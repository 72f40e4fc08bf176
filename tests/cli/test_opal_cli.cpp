// `packlab generate fba` and `packlab build opal` end to end: the FBA report states the target
// porosity and an overlap below the tolerance, the written packing passes an independent check,
// the same seed gives the same packing; the opal model file carries types, fixed flags and bonds
// as reported; bad input exits with code 2 naming the key.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/generate/opal.hpp"
#include "packlab/io/packing_io.hpp"

using namespace packlab;
using packlab::test::run_packlab;
using packlab::test::TempDir;

namespace {

nlohmann::json read_json(const std::string& path) {
  std::ifstream f(path);
  return nlohmann::json::parse(f);
}

}  // namespace

TEST(OpalCli, FbaThenFccOpalWithCoating) {
  TempDir dir("opal-cli");
  // 12 x 10.39 x 16.7 box of unit spheres: [111] pore lattice with D = 6 fits twice along x, once along y.
  const auto fba = run_packlab("generate fba --box 12,10.392304845413264,16.696938456699067 --diameter 1 "
                               "--porosity 0.40 --periodic xy --seed 3 --no-plots --quiet --out " +
                               dir.file("fba"));
  ASSERT_EQ(fba.exit_code, 0) << fba.output;
  const auto r = read_json(dir.file("fba/report.json"));
  EXPECT_EQ(r["results"]["stop"], "target_reached");
  EXPECT_NEAR(r["results"]["porosity"].get<double>(), 0.40, 2e-3);  // count rounded to whole spheres
  EXPECT_LE(r["results"]["verified_max_overlap"].get<double>(), 1e-3);
  const Packing p = io::read_packing(dir.file("fba/packing.xyz"));
  EXPECT_EQ(long(p.size()), r["parameters"]["particles"].get<long>());
  EXPECT_LE(generate::brute_force_max_overlap(p), 1e-3 + 1e-9);
  EXPECT_TRUE(p.box.periodic[0] && p.box.periodic[1] && !p.box.periodic[2]);

  // Same seed, same packing.
  const auto again = run_packlab("generate fba --box 12,10.392304845413264,16.696938456699067 --diameter 1 "
                                 "--porosity 0.40 --periodic xy --seed 3 --no-plots --quiet --out " +
                                 dir.file("fba2"));
  ASSERT_EQ(again.exit_code, 0) << again.output;
  const Packing q = io::read_packing(dir.file("fba2/packing.xyz"));
  ASSERT_EQ(p.size(), q.size());
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_NEAR(norm(p.position[i] - q.position[i]), 0.0, 1e-12);

  const auto opal = run_packlab("build opal " + dir.file("fba/packing.vtu") +
                                " --pores fcc --pore-diameter 6 --coating 0.6 --quiet --out " + dir.file("opal"));
  ASSERT_EQ(opal.exit_code, 0) << opal.output;
  const auto o = read_json(dir.file("opal/report.json"));
  const Packing m = io::read_packing(dir.file("opal/opal.vtu"));
  EXPECT_EQ(long(m.size()), o["results"]["particles"].get<long>());
  EXPECT_EQ(long(m.bonds.size()), o["results"]["bonds"].get<long>());
  EXPECT_TRUE(o["results"]["lattice_commensurate"].get<bool>());
  EXPECT_GT(o["results"]["titania_particles"].get<long>(), 0);
  EXPECT_EQ(o["parameters"]["bond_radius_ratio"].get<double>(), 1.0);
  long fixed = 0, substrate = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    fixed += m.fixed[i];
    substrate += m.type[i] == particle_type::substrate;
    EXPECT_EQ(m.fixed[i] == 1, m.type[i] == particle_type::substrate);
  }
  EXPECT_EQ(substrate, o["results"]["substrate_particles"].get<long>());
  for (std::size_t b = 0; b < m.bonds.size(); ++b)
    ASSERT_EQ(m.bonds.material[b], generate::opal_bond_material_of(m.type[std::size_t(m.bonds.i[b])],
                                                                   m.type[std::size_t(m.bonds.j[b])]));
  // Random pores on the same packing.
  const auto rnd = run_packlab("build opal " + dir.file("fba/packing.vtu") +
                               " --pores random --pore-ratio 4 --pore-count 6 --seed 2 --quiet --out " +
                               dir.file("rnd"));
  ASSERT_EQ(rnd.exit_code, 0) << rnd.output;
  EXPECT_EQ(read_json(dir.file("rnd/report.json"))["results"]["pores"].get<long>(), 6);
}

TEST(OpalCli, BadInputExitsWithCodeTwoNamingTheKey) {
  TempDir dir("opal-cli-bad");
  auto r = run_packlab("generate fba --particles 100 --porosity 0.2 --quiet --out " + dir.file("a"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("porosity = 0.2"), std::string::npos) << r.output;  // the key of the flag and the file
  r = run_packlab("generate fba --particles 100 --periodic xq --quiet --out " + dir.file("b"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("periodic = xq"), std::string::npos) << r.output;
  r = run_packlab("generate fba --particles 300 --porosity 0.4 --quiet --no-plots --out " + dir.file("c"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_packlab("build opal " + dir.file("c/packing.xyz") + " --pore-ratio 3 --bond-cutoff 2.5 --out " +
                  dir.file("d"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("bond_cutoff = 2.5"), std::string::npos) << r.output;
  r = run_packlab("build opal " + dir.file("c/packing.xyz") + " --pore-ratio 3 --orientation 110 --out " +
                  dir.file("e"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("orientation = 110"), std::string::npos) << r.output;
}
