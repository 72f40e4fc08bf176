// The void expansion method (vem-void-expansion-method §2.2): box, blow-up, void growth, the
// structural CN, mass scaling, checkpoints, bad input and the command line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "../cli/cli_runner.hpp"
#include "packlab/core/error.hpp"
#include "packlab/generate/vem.hpp"
#include "small_vem.hpp"

using namespace packlab;
using namespace packlab::generate;

namespace {

// A small, fast case: 120 structural and 60 void particles (n = 0.5), voids grown by 0.05 r_S.
VemParams tiny() {
  VemParams p = test::small_vem(120, 60, 0.35, 0.4, 400);
  p.relax_check_interval = 25;
  p.seed = 3;
  return p;
}

double sphere_volume(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }

bool same_rows(const std::vector<VemRow>& a, const std::vector<VemRow>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const VemRow &x = a[k], &y = b[k];
    if (x.cycle != y.cycle || x.q != y.q || x.cn != y.cn || x.phi_total != y.phi_total ||
        x.strain_energy != y.strain_energy || x.kinetic_energy != y.kinetic_energy || x.steps != y.steps ||
        x.unbalanced_force_ratio != y.unbalanced_force_ratio || x.converged != y.converged)
      return false;
  }
  return true;
}

}  // namespace

TEST(Vem, BoxEdgeIsEquationThree) {
  // l = r_S (4 pi N_S / (3 Phi_S))^(1/3): N_S sphere volumes fill Phi_S of the cube.
  for (auto [n, r, phi] : {std::tuple{8000L, 2.5e-7, 0.4}, {4000L, 1.0, 0.2}, {123L, 3e-3, 0.55}}) {
    const double l = vem_box_edge(n, r, phi);
    EXPECT_NEAR(static_cast<double>(n) * sphere_volume(r) / (l * l * l), phi, 1e-14 * phi);
  }
  const VemParams p = tiny();
  const Vem vem(p);
  const Packing packing = vem.packing();
  const double l = vem_box_edge(p.structural, p.radius, p.phi_s);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(packing.box.length[a], l);
    EXPECT_TRUE(packing.box.periodic[a]);
  }
  long structural = 0, voids = 0;
  for (int t : packing.type) (t == particle_type::structural ? structural : voids) += 1;
  EXPECT_EQ(structural, p.structural);
  EXPECT_EQ(voids, p.voids);
}

TEST(Vem, BlowUpReachesStructuralRadiusAfterMSteps) {
  VemParams p = tiny();
  p.blowup_steps = 4;
  Vem vem(p);
  const double r_v0 = p.void_radius_ratio * p.radius;
  auto radii = [&](int type) {
    std::vector<double> r;
    const Packing packing = vem.packing();
    for (std::size_t i = 0; i < packing.size(); ++i)
      if (packing.type[i] == type) r.push_back(packing.radius[i]);
    return r;
  };
  for (double r : radii(particle_type::structural)) EXPECT_EQ(r, p.radius / 5.0);  // r_S / (m + 1)
  int seen = 0;
  while (vem.stage() == VemStage::blowup) {
    vem.run(1);
    if (vem.blowup_done() != seen) {
      seen = vem.blowup_done();
      const double expected = seen == p.blowup_steps ? p.radius : (seen + 1) * p.radius / 5.0;
      for (double r : radii(particle_type::structural)) EXPECT_DOUBLE_EQ(r, expected);
      for (double r : radii(particle_type::void_particle)) EXPECT_EQ(r, r_v0);  // voids wait
    }
  }
  EXPECT_EQ(seen, p.blowup_steps);
  for (double r : radii(particle_type::structural)) EXPECT_EQ(r, p.radius);  // exactly r_S
  ASSERT_EQ(vem.curve().size(), 1u);
  EXPECT_DOUBLE_EQ(vem.curve()[0].q, p.void_radius_ratio);
}

TEST(Vem, VoidsGrowByTheirInitialRadiusPerCycleAndPhiTotalIsEquationFive) {
  Vem vem(tiny());
  vem.run();
  const auto& curve = vem.curve();
  ASSERT_GE(curve.size(), 3u);
  for (std::size_t k = 0; k < curve.size(); ++k) {
    EXPECT_EQ(curve[k].cycle, static_cast<long>(k));
    EXPECT_DOUBLE_EQ(curve[k].q, static_cast<double>(k + 1) * 0.05);
  }
  EXPECT_EQ(vem.stop_reason(), VemStop::max_q);
  EXPECT_LE(curve.back().q, vem.params().max_q + 1e-12);
  // Eq. 5 against the spheres actually in the box at the end.
  EXPECT_NEAR(curve.back().phi_total, vem.packing().volume_fraction(), 1e-12);
  // The structural packing has the voids removed.
  const Packing s = vem.structural_packing();
  EXPECT_EQ(static_cast<long>(s.size()), vem.params().structural);
  for (int t : s.type) EXPECT_EQ(t, particle_type::structural);
}

TEST(Vem, StructuralCoordinationCountsStructuralPairsWithinOnePercentGap) {
  Packing p;
  p.box.length = {20.0, 20.0, 20.0};
  const double r = 1.0;
  p.add({2, 2, 2}, r);
  p.add({2 + 2 * r * 1.009, 2, 2}, r);  // gap 0.9 % of 2 r_S: a contact
  p.add({10, 10, 10}, r);
  p.add({10 + 2 * r * 1.011, 10, 10}, r);                     // gap 1.1 %: not a contact
  p.add({2, 2 + 2 * r, 2}, r, particle_type::void_particle);  // touching a structural particle: ignored
  p.add({10, 10 + 1.5 * r, 10}, 0.5 * r, particle_type::void_particle);
  EXPECT_DOUBLE_EQ(structural_coordination(p, 0.01), 2.0 / 4.0);
  EXPECT_DOUBLE_EQ(structural_coordination(p, 0.02), 4.0 / 4.0);
  // Across the periodic boundary as well.
  Packing q;
  q.box.length = {20.0, 20.0, 20.0};
  q.add({0.5, 5, 5}, r);
  q.add({20.0 + 0.5 - 2 * r * 1.005, 5, 5}, r);
  EXPECT_DOUBLE_EQ(structural_coordination(q, 0.01), 1.0);
}

TEST(Vem, VoidMassScaling) {
  VemParams p = tiny();
  const double m_s = p.structural_material.density * sphere_volume(p.radius / (p.blowup_steps + 1));
  // Stiffest contacts (particle stiffnesses in series): a void's with a structural particle,
  // a structural particle's with another.
  const double k_v = 1e3 * 1e2 / (1e3 + 1e2), k_s = 1e3 / 2.0;
  const double true_mass = p.void_material.density * sphere_volume(p.void_radius_ratio * p.radius);
  for (double c : {1.0, 0.25, 0.0}) {
    p.void_mass_scaling = c;
    const Vem vem(p);
    const double expected = std::max(true_mass, c * m_s * k_v / k_s);
    const ParticleStore& P = vem.engine().particles();
    for (std::size_t k = 0; k < P.size(); ++k) {
      if (P.type[k] != particle_type::void_particle) continue;
      EXPECT_NEAR(P.mass[k], expected, 1e-12 * expected);
      const double inertia = 0.4 * expected * P.radius[k] * P.radius[k];
      EXPECT_NEAR(P.inverse_inertia[k], 1.0 / inertia, 1e-12 / inertia);
    }
  }
}

TEST(Vem, CheckpointResumeEqualsUninterruptedRun) {
  const VemParams p = tiny();
  Vem straight(p);
  straight.run();
  ASSERT_TRUE(straight.finished());
  const long total = straight.total_steps();
  // Break once inside the blow-up and once inside an expansion relaxation.
  Vem first(p);
  first.run(1234);
  ASSERT_EQ(first.stage(), VemStage::blowup);
  std::stringstream s1;
  first.save_checkpoint(s1);
  auto second = Vem::resume(s1);
  second->run(total - 1234 - 777);
  ASSERT_EQ(second->stage(), VemStage::expansion);
  std::stringstream s2;
  second->save_checkpoint(s2);
  auto third = Vem::resume(s2, 0, false);  // adapt_threads changes no result
  EXPECT_TRUE(second->engine().config().adapt_threads);
  EXPECT_FALSE(third->engine().config().adapt_threads);
  third->run();
  ASSERT_TRUE(third->finished());
  EXPECT_EQ(third->total_steps(), total);
  EXPECT_TRUE(same_rows(third->curve(), straight.curve()));
  EXPECT_EQ(third->stop_reason(), straight.stop_reason());
  EXPECT_TRUE(third->engine().particles().position == straight.engine().particles().position);
  EXPECT_TRUE(third->engine().particles().velocity == straight.engine().particles().velocity);
  EXPECT_EQ(third->engine().time(), straight.engine().time());
}

// stop.min_coordination: stage III ends the run only once CN has reached the minimum as well;
// until then the run is the same trajectory as without it, and a minimum below the stage III
// coordination changes nothing.
TEST(Vem, StageThreeStopWaitsForTheMinimumCoordination) {
  VemParams p = tiny();
  p.max_q = 2.0;
  Vem plain(p);
  plain.run();
  ASSERT_EQ(plain.stop_reason(), VemStop::stage_three);
  const std::vector<VemRow>& rows = plain.curve();
  const double end_cn = rows.back().cn;
  const double scale = static_cast<double>(p.structural) * p.structural_material.normal_stiffness * p.radius * p.radius;

  p.stop_min_coordination = end_cn + 0.05;
  Vem longer(p);
  longer.run();
  const std::vector<VemRow>& more = longer.curve();
  ASSERT_GT(more.size(), rows.size());
  EXPECT_TRUE(same_rows(std::vector<VemRow>(more.begin(), more.begin() + static_cast<long>(rows.size())), rows));
  ASSERT_EQ(longer.stop_reason(), VemStop::stage_three) << "the tiny run reached max_q first";
  EXPECT_GE(more.back().cn, p.stop_min_coordination);
  EXPECT_GE(more.back().strain_energy / scale, p.stop_strain_energy);
  for (std::size_t k = 0; k + 1 < more.size(); ++k)
    EXPECT_TRUE(more[k].cn < p.stop_min_coordination || more[k].strain_energy / scale < p.stop_strain_energy)
        << "row " << k << " met both criteria";

  p.stop_min_coordination = 0.5 * end_cn;
  Vem same(p);
  same.run();
  EXPECT_EQ(same.stop_reason(), VemStop::stage_three);
  EXPECT_TRUE(same_rows(same.curve(), rows));
}

// DESIGN.md: the same seed gives the same packing whatever the thread count: a small run at
// 1 and 2 threads, compared bit for bit (the engine adds every particle's forces, and the
// diagnostics VEM's relaxations stop on, in single-thread order; vem.cpp draws nothing per
// thread).
namespace {

VemParams small_threaded(int threads) {
  VemParams p = test::small_vem(60, 30, 0.35, 0.25, 200);
  p.relax_check_interval = 25;
  p.seed = 7;
  p.threads = threads;
  return p;
}

bool same_run(const Vem& a, const Vem& b) {
  return a.total_steps() == b.total_steps() && same_rows(a.curve(), b.curve()) &&
         a.engine().particles().position == b.engine().particles().position &&
         a.engine().particles().velocity == b.engine().particles().velocity;
}

}  // namespace

// 1200 steps: through the blow-up into the void growth (the run ends at 1485), with ten
// renumberings of the particles on the way (resort_particles). Two threads on a loaded machine
// wait at every barrier, so a whole run would take seconds.
constexpr long threaded_steps = 1200;

TEST(Vem, OneResultPerSeedWhateverTheThreadCount) {
  Vem one(small_threaded(1)), two(small_threaded(2));
  one.run(threaded_steps);
  two.run(threaded_steps);
  ASSERT_EQ(one.stage(), VemStage::expansion);
  EXPECT_TRUE(same_run(one, two));
}

TEST(Vem, OneResultPerSeedForAFixedThreadCount) {
  Vem a(small_threaded(2)), b(small_threaded(2));
  a.run(threaded_steps);
  b.run(threaded_steps);
  ASSERT_EQ(a.stage(), VemStage::expansion);
  EXPECT_TRUE(same_run(a, b));
}

TEST(Vem, BadInputIsAnInputError) {
  const auto bad = [](auto change) {
    VemParams p = tiny();
    change(p);
    EXPECT_THROW(p.validate(), InputError);
    EXPECT_THROW(Vem{p}, InputError);
  };
  bad([](VemParams& p) { p.phi_s = 0.7; });
  bad([](VemParams& p) { p.phi_s = 0.0; });
  bad([](VemParams& p) { p.radius = -1e-7; });
  bad([](VemParams& p) { p.voids = 0; });
  bad([](VemParams& p) { p.structural = 1; });
  bad([](VemParams& p) { p.blowup_steps = 0; });
  bad([](VemParams& p) { p.void_radius_ratio = 0.0; });
  bad([](VemParams& p) { p.relax_tolerance = -1.0; });
  bad([](VemParams& p) { p.relax_max_steps = 0; });
  bad([](VemParams& p) { p.void_material.damping = 1.0; });
  bad([](VemParams& p) { p.structural_material.normal_stiffness = -1.0; });
  bad([](VemParams& p) { p.void_mass_scaling = -1.0; });
  bad([](VemParams& p) { p.stop_min_coordination = -1.0; });
  bad([](VemParams& p) { p.stop_min_coordination = 13.0; });
  VemParams p = tiny();
  p.structural = 10;
  p.max_q = 3.0;  // the box (4.9 r_S) cannot hold two voids of 3 r_S
  try {
    p.validate();
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("max_q"), std::string::npos) << e.what();
  }
  std::stringstream garbage("not a checkpoint at all");
  EXPECT_THROW(Vem::resume(garbage), InputError);
  Vem vem(tiny());
  std::stringstream full;
  vem.save_checkpoint(full);
  std::stringstream truncated(full.str().substr(0, full.str().size() / 2));
  EXPECT_THROW(Vem::resume(truncated), InputError);
}

// --- command line -------------------------------------------------------------------------

namespace {

void write_config(const std::string& path, const std::string& extra = "") {
  std::ofstream f(path);
  f << "structural = 100\nvoids = 50\nphi_s = 0.35\nvoid_radius_ratio = 0.05\nthreads = 1\nseed = 5\n"
       "[relax]\nmax_steps = 300\ncheck_interval = 25\n[stop]\nmax_q = 0.3\n"
    << extra;
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream f(path);
  return nlohmann::json::parse(f);
}

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace

TEST(VemCli, WritesPackingCurveReportAndResumesFinishedRun) {
  test::TempDir dir("vem-cli");
  write_config(dir.file("vem.toml"));
  const auto out = dir.file("run");
  const auto r = test::run_packlab("generate vem --config " + dir.file("vem.toml") +
                                   " --structural 110 --no-plots --quiet --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"packing.xyz", "packing.vtu", "cn_curve.csv", "report.json", "checkpoint.bin"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  const auto report = read_json(out + "/report.json");
  EXPECT_EQ(report["structural"], 110);  // the flag overrides the file
  EXPECT_EQ(report["voids"], 50);
  EXPECT_DOUBLE_EQ(report["phi_s"].get<double>(), 0.35);
  for (const char* key : {"inflection", "beta", "beta_r2", "seconds", "stop_reason", "mass_scaling"})
    EXPECT_TRUE(report.contains(key)) << key;
  const std::string csv = read_text(out + "/cn_curve.csv");
  EXPECT_NE(csv.find("q,cn,phi_total,strain_energy,kinetic_energy,steps"), std::string::npos);
  // 0.05 .. 0.30: six rows.
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3 + 6);
  const auto again = test::run_packlab("generate vem --resume " + out + " --adapt-threads=false --no-plots --quiet");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(read_text(out + "/cn_curve.csv"), csv);
}

TEST(VemCli, UnknownConfigKeyAndBadValuesExitWithCodeTwo) {
  test::TempDir dir("vem-cli-bad");
  write_config(dir.file("typo.toml"), "tolerence = 1e-3\n");  // lands in [stop]
  auto r = test::run_packlab("generate vem --config " + dir.file("typo.toml") + " --quiet --out " + dir.file("o"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("stop.tolerence"), std::string::npos) << r.output;
  write_config(dir.file("ok.toml"));
  r = test::run_packlab("generate vem --config " + dir.file("ok.toml") + " --phi-s 0.9 --quiet --out " + dir.file("o"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("phi_s"), std::string::npos) << r.output;
  r = test::run_packlab("generate vem --resume " + dir.file("nothing-here") + " --quiet");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("checkpoint"), std::string::npos) << r.output;
}

TEST(VemCli, EveryExampleConfigIsValid) {
  // The configs of examples/vem/ (docs/vem.md) parse and pass validation.
  int count = 0;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(std::filesystem::path(PACKLAB_SOURCE_DIR) / "examples" / "vem")) {
    if (entry.path().extension() != ".toml") continue;
    ++count;
    const auto r = test::run_packlab("generate vem --check --config " + entry.path().string() + " --out /nonexistent");
    EXPECT_EQ(r.exit_code, 0) << entry.path() << ": " << r.output;
    EXPECT_NE(r.output.find("parameters valid"), std::string::npos) << r.output;
  }
  EXPECT_GE(count, 1 + 8 + 5 + 17);  // Fig. 1, the n-, Phi_S- and stiffness studies
}
