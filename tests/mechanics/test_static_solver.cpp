// The quasi-static solver (mechanics/static_solver.hpp, static_loading.hpp): closed forms of
// lattices (shear between plates, the periodic stiffness tensor, compression of beam-bond
// columns), Clapeyron's theorem, sequential linear analysis of a uniform column, agreement with
// the dynamic tests on disordered models, the two factorization backends, the preconditioned
// re-solve after bonds break, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "../test_packings.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/generate/lattice.hpp"
#include "packlab/mechanics/opal_materials.hpp"
#include "packlab/mechanics/static_loading.hpp"
#include "silica_compression.hpp"

using namespace packlab;
using namespace packlab::mechanics;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double r0 = 0.25e-6;           // shear tests' particles
constexpr double r = 7.5e-9;             // the opal paper's 15 nm particles
constexpr double E = 6.53e9, nu = 0.17;  // silica bonds

OscillatoryShearOptions shear_options(const std::string& solver, const std::string& orientations = "z:x") {
  OscillatoryShearOptions o;
  o.stiffness_rule = "contact";
  o.normal_stiffness = 100.0;
  o.shear_stiffness = 10.0;
  o.normal_strength = o.shear_strength = inf;
  o.cycles = 2;
  o.steps_per_cycle = 4000;
  o.samples_per_cycle = 40;
  o.orientations = orientations;
  o.threads = 1;
  o.solver = solver;
  return o;
}

UniaxialCompressionOptions compression_options(const std::string& solver, double strength = inf) {
  UniaxialCompressionOptions o = test::silica_compression_options(E, nu, strength);
  o.solver = solver;
  return o;
}

// The constrained modulus of a periodic simple cubic column with bonds to 1.75 d (axial, face
// and body diagonals): see tests/mechanics/test_uniaxial_compression.cpp.
double sc_modulus() {
  const double G = E / (2 * (1 + nu));
  return std::numbers::pi / 4 * (E + std::sqrt(2.0) * (E + G) + 4 * (E + 2 * G) / (3 * std::sqrt(3.0)));
}

// An FCC network of contact bonds with a deterministic 30 % of its bonds removed.
Packing diluted_fcc(double keep) {
  Packing p = test::bonded_lattice(generate::LatticeType::fcc, {3, 3, 3}, r0, 1.01);
  Bonds kept;
  Random rng(7);
  for (std::size_t b = 0; b < p.bonds.size(); ++b)
    if (rng.uniform() < keep) kept.add(p.bonds.i[b], p.bonds.j[b], p.bonds.image[b], 0, p.bonds.rest_length[b]);
  p.bonds = kept;
  return p;
}

Packing random_bonded_sample(long n, unsigned seed) { return test::random_bonded_sample(n, seed, r); }

// The sequential linear analysis of a random sample to 5 % strain, one thread, with eq. 16 on
// compressed bonds too (its peak then lies near 2 % strain, well before the end of the run).
UniaxialCompressionSetup static_compression_to_five_percent(const Packing& p) {
  UniaxialCompressionSetup setup;
  setup.options.threads = 1;
  setup.options.max_strain = 0.05;
  setup.finish(p);
  for (auto& b : setup.options.bond_materials) b.compressive_breakage = true;
  setup.options.solver = "static";
  return setup;
}

dem::EngineConfig contact_bond_config(double kn, double ks) {
  dem::EngineConfig c;
  c.contact_law = "linear";
  c.stiffness_rule = dem::StiffnessRule::contact;
  c.types = {dem::Material{.normal_stiffness = kn, .shear_stiffness = ks}};
  c.bond_materials = dem::BondMaterialList<dem::ContactBond>{dem::ContactBond::Params{kn, ks, inf, inf}};
  return c;
}

// Three particles of radius r0 on a line along x, joined by two contact bonds whose gap `gap`
// (the centre distance minus 2 r0) gives each the tension N = k_n gap (gap < 0: an overlap,
// compression).
Packing string_of_three(double gap) {
  Packing p = test::open_cube(10.0 * r0);
  const double L = 2.0 * r0 + gap;
  for (int k = 0; k < 3; ++k) p.add(Vec3{5.0 * r0 + (k - 1) * L, 5.0 * r0, 5.0 * r0}, r0);
  p.bonds.add(0, 1, {0, 0, 0}, 0, L);
  p.bonds.add(1, 2, {0, 0, 0}, 0, L);
  return p;
}

}  // namespace

// The geometric stiffness of a pre-stress (static_stiffness.hpp) on a string: particles 0 and 2
// prescribed, 1 free, two contact bonds of tension N (L apart). Across the string the free
// particle's translational stiffness is 2 k_s + 2 N / L (2 k_s without the term); moving it
// across by delta turns the engine's pre-forces by -(2 N / L) delta, the term's force; and with
// particle 2 moved across by delta the free particle rolls to delta / 2 with both shear springs
// unloaded, so that particle 2 feels only its link's turned pre-force, -(N / L) delta / 2.
// Tension stiffens, compression softens: a flipped sign fails every check.
TEST(StaticSolver, GeometricStiffnessOfAPrestressedStringIsTwoNOverL) {
  const double kn = 100.0, ks = 10.0;
  const dem::EngineConfig config = contact_bond_config(kn, ks);
  const std::vector<std::uint8_t> prescribed{1, 0, 1};
  for (const double gap : {2e-3 * r0, -2e-3 * r0}) {
    SCOPED_TRACE(gap > 0.0 ? "tension" : "compression");
    const Packing p = string_of_three(gap);
    const double L = 2.0 * r0 + gap, N = kn * gap, g = N / L;
    const StaticLinks plain = linearize_links(p, config);
    EXPECT_TRUE(plain.prestress.empty());
    const StaticLinks links = linearize_links(p, config, true);
    ASSERT_EQ(links.size(), 2u);
    ASSERT_EQ(links.prestress.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) EXPECT_NEAR(links.prestress[k], N, 1e-9 * std::abs(N));

    StiffnessAssembly with(links, prescribed), without(plain, prescribed);
    with.assemble({}, 0.0);
    without.assemble({}, 0.0);
    auto diagonal = [](const StiffnessAssembly& a, int c) {
      return a.values()[static_cast<std::size_t>(a.column_start()[static_cast<std::size_t>(c)])];
    };
    EXPECT_NEAR(diagonal(with, 0), 2.0 * kn, 1e-12 * kn);  // along the string: the springs alone
    for (int c : {1, 2}) {
      EXPECT_NEAR(diagonal(without, c), 2.0 * ks, 1e-12 * ks);
      EXPECT_NEAR(diagonal(with, c), 2.0 * ks + 2.0 * g, 1e-9 * ks);
    }
    for (std::size_t k = 0; k < 2; ++k) {  // each link's 12 x 12 matrix stays symmetric
      const auto K = link_stiffness(links, k);
      for (std::size_t a = 0; a < 6; ++a)
        for (std::size_t b = 0; b < 6; ++b) {
          EXPECT_EQ(K[0][6 * a + b], K[0][6 * b + a]);
          EXPECT_EQ(K[3][6 * a + b], K[3][6 * b + a]);
          EXPECT_EQ(K[1][6 * a + b], K[2][6 * b + a]);
        }
    }

    // The engine's forces with the free particle moved across (a fresh engine: no shear history).
    const double delta = 1e-7 * L;
    Packing moved = p;
    moved.position[1].y += delta;
    const dem::ContactForces f = dem::Engine(moved, config).contact_forces();
    double engine_fy = 0.0;
    for (std::size_t c = 0; c < f.size(); ++c) {
      if (f.j[c] == 1) engine_fy += f.force[c].y;
      if (f.i[c] == 1) engine_fy -= f.force[c].y;
    }
    EXPECT_NEAR(engine_fy, -2.0 * g * delta, 1e-5 * 2.0 * std::abs(g) * delta);
    std::vector<double> q(18, 0.0);
    q[7] = delta;
    const double term_fy =
        link_response(links, 0, q, {}).geometric_force_on_j.y - link_response(links, 1, q, {}).geometric_force_on_j.y;
    EXPECT_NEAR(term_fy, engine_fy, 1e-5 * std::abs(engine_fy));

    // A solve with particle 2 moved across.
    for (const StaticLinks* l : {&links, &plain}) {
      StaticSolver solver(*l, prescribed, {});
      std::vector<double> u(18, 0.0);
      u[13] = delta;
      solver.solve(u, {});
      EXPECT_NEAR(u[7], 0.5 * delta, 1e-9 * delta);
      const LinkResponse r = link_response(*l, 1, u, {});
      const double expected = l == &links ? -g * 0.5 * delta : 0.0;
      EXPECT_NEAR(r.force_on_j.y, expected, 1e-7 * std::abs(g) * delta);
    }
  }
}

// The closed form of tests/mechanics/test_oscillatory_shear.cpp (n layers of a simple cubic
// network of contact bonds between rigid plates): G = k_s n / ((2n + 1) d), in all six
// orientations, from the region stresses and from the plate force, phase angle zero.
TEST(StaticSolver, SimpleCubicShearBetweenPlatesMatchesTheClosedForm) {
  const Packing sc = test::bonded_lattice(generate::LatticeType::sc, {4, 4, 4}, r0, 1.01);
  OscillatoryShearOptions o = shear_options("static", "all");
  o.regions = 1;
  const OscillatoryShearResult res = run_oscillatory_shear(sc, o);
  const double d = 2.0 * r0, n = 4.0;
  const double expected = o.shear_stiffness * n / ((2.0 * n + 1.0) * d);
  ASSERT_EQ(res.runs.size(), 6u);
  for (const auto& run : res.runs) {
    EXPECT_EQ(run.solver, "static");
    EXPECT_NEAR(run.storage_modulus, expected, 1e-8 * expected) << orientation_name(run.orientation);
    EXPECT_NEAR(run.plate_storage_modulus, expected, 1e-8 * expected) << orientation_name(run.orientation);
    EXPECT_LT(std::abs(run.phase_angle), 1e-12);
  }
}

// Periodic simple cubic lattice of contact bonds under affine strain, rotations free: a bond
// along z sheared by gamma d has both ends turning by gamma / 2, which halves its shear
// (G = k_s / (2 d) = k_s / (4 r)); along an axis only the normal springs act (C11 = k_n / d), and
// nothing couples the axes (C12 = 0, Poisson's ratio 0, E = C11).
TEST(StaticSolver, PeriodicSimpleCubicLatticeStiffnessTensorIsTheClosedForm) {
  const Packing sc = test::bonded_lattice(generate::LatticeType::sc, {3, 3, 3}, r0, 1.01);
  const double kn = 100.0, ks = 10.0, d = 2.0 * r0;
  const PeriodicStiffness c = periodic_stiffness(sc, contact_bond_config(kn, ks));
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(c.stiffness[a][a], kn / d, 1e-8 * kn / d);
    EXPECT_NEAR(c.stiffness[a + 3][a + 3], ks / (2.0 * d), 1e-8 * ks / d);
    EXPECT_NEAR(c.stiffness[a][(a + 1) % 3], 0.0, 1e-8 * kn / d);
    EXPECT_NEAR(c.youngs_modulus[static_cast<std::size_t>(a)], kn / d, 1e-8 * kn / d);
    EXPECT_NEAR(c.poisson_ratio[static_cast<std::size_t>(a)], 0.0, 1e-8);
  }
  EXPECT_NEAR(c.shear_modulus, ks / (2.0 * d), 1e-8 * ks / d);
}

// Elastic beam bonds along the axes only (cutoff 1.01 d), radius ratio 1: each column carries
// E_b pi r^2 / d per gap on a cross-section d^2, so E = (pi / 4) E_b; the diagonal bonds of a
// 1.75 d cutoff add the closed form of the dynamic test. To solver tolerance.
TEST(StaticSolver, SimpleCubicColumnsOfBeamBondsGiveTheClosedFormModulus) {
  UniaxialCompressionOptions o = compression_options("static");
  o.max_strain = 0.003;
  const UniaxialCompressionResult axial =
      run_uniaxial_compression(test::bonded_lattice(generate::LatticeType::sc, {3, 3, 8}, r, 1.01), o);
  EXPECT_EQ(axial.solver, "static");
  EXPECT_NEAR(axial.height, 5 * 2 * r, 1e-9 * r);
  EXPECT_NEAR(axial.youngs_modulus, std::numbers::pi / 4 * E, 1e-8 * E);
  EXPECT_EQ(axial.broken_bonds, 0u);
  EXPECT_EQ(axial.stop_reason, "reached max_strain");
  EXPECT_NEAR(axial.curve.back().stress, std::numbers::pi / 4 * E * 0.003, 1e-8 * E * 0.003);

  const UniaxialCompressionResult diagonal =
      run_uniaxial_compression(test::bonded_lattice(generate::LatticeType::sc, {3, 3, 8}, r, 1.75), o);
  EXPECT_NEAR(diagonal.youngs_modulus, sc_modulus(), 1e-8 * sc_modulus());
  // Open sides: the lattice's columns do not couple laterally; no lateral strain.
  o.sides = "open";
  const UniaxialCompressionResult open =
      run_uniaxial_compression(test::bonded_lattice(generate::LatticeType::sc, {3, 3, 8}, r, 1.01), o);
  EXPECT_NEAR(open.poisson_ratio, 0.0, 1e-8);
}

// Clapeyron: the work of the plate, F delta / 2, equals the strain energy of the links; and
// Poisson's ratio of an open disordered pillar is positive and below 1/2.
TEST(StaticSolver, PlateWorkEqualsTheStrainEnergyOfTheLinks) {
  const Packing p = random_bonded_sample(300, 3);
  UniaxialCompressionOptions o = compression_options("static");
  o.max_strain = 0.01;
  o.sides = "open";
  const UniaxialCompressionResult res = run_uniaxial_compression(p, o);
  const UniaxialCompressionPoint& last = res.curve.back();
  ASSERT_GT(last.strain_energy, 0.0);
  EXPECT_NEAR(0.5 * last.force * last.displacement, last.strain_energy, 1e-7 * last.strain_energy);
  EXPECT_GT(res.poisson_ratio, 0.0);
  EXPECT_LT(res.poisson_ratio, 0.5);
}

// A uniform column whose bonds all carry the same axial stress E_b eps: with the normal
// criterion on compressed bonds (eq. 16 as written), all the gauge's axial bonds reach
// sigma_max together at eps = sigma_max / E_b, where the stress is (pi / 4) sigma_max. Those
// that tie to round-off break at once (at least one per column, 9 columns, at most the 45 of
// the 5 gaps); once every column is cut it carries nothing and the analysis stops.
TEST(StaticSolver, SequentialLinearAnalysisOfAUniformColumnBreaksItAtTheClosedFormStrength) {
  const double strength = 50e6;
  UniaxialCompressionOptions o = compression_options("static", strength);
  for (auto& b : o.bond_materials) b.compressive_breakage = true;
  o.max_strain = 0.05;
  const UniaxialCompressionResult res =
      run_uniaxial_compression(test::bonded_lattice(generate::LatticeType::sc, {3, 3, 8}, r, 1.01), o);
  EXPECT_NEAR(res.strain_at_peak, strength / E, 1e-8 * strength / E);
  EXPECT_NEAR(res.strength, std::numbers::pi / 4 * strength, 1e-8 * strength);
  EXPECT_GE(res.broken_bonds, 9u);
  EXPECT_LE(res.broken_bonds, 45u);
  EXPECT_LT(res.curve.back().stress, 1e-6 * res.strength);
  ASSERT_EQ(res.break_strain.size(), res.broken_bonds);
  for (double s : res.break_strain) EXPECT_NEAR(s, strength / E, 1e-8 * strength / E);
  EXPECT_NE(res.stop_reason, "reached max_strain");
  // Without the normal criterion on compressed bonds (MUSEN's default), the column never fails.
  o.bond_materials = compression_options("static", strength).bond_materials;
  const UniaxialCompressionResult tough =
      run_uniaxial_compression(test::bonded_lattice(generate::LatticeType::sc, {3, 3, 8}, r, 1.01), o);
  EXPECT_EQ(tough.broken_bonds, 0u);
}

// The static and the dynamic test on the same disordered models: G' of a diluted FCC network of
// contact bonds within 2 %, and E of the random bonded sample within 2 %, strength within 10 %
// (the dynamic one at the automatic quasi-static rate, rate-independent to 5 %:
// tests/mechanics/test_uniaxial_compression.cpp).
// The network has a gap of 1e-3 d between neighbours and is sheared to 1e-4, so that no unbonded
// neighbour pair closes: with the lattice touching (gap 0) the dynamic test's unbonded
// neighbours push whenever they are compressed and its G' is 37 % above the static one, whose
// contacts are only those touching at the start.
TEST(StaticSolver, AgreesWithTheDynamicShearTestOnADisorderedNetwork) {
  generate::LatticeParams lp;
  lp.type = generate::LatticeType::fcc;
  lp.cells = {3, 3, 3};
  lp.radius = r0;
  lp.gap = 1e-3 * 2 * r0;
  Packing p = generate::make_lattice(lp);
  generate::BondingOptions bo;
  bo.cutoff_ratio = 1.01;
  generate::add_bonds(p, bo);
  Bonds kept;
  Random rng(7);
  for (std::size_t b = 0; b < p.bonds.size(); ++b)
    if (rng.uniform() < 0.7) kept.add(p.bonds.i[b], p.bonds.j[b], p.bonds.image[b], 0, p.bonds.rest_length[b]);
  p.bonds = kept;
  OscillatoryShearOptions o = shear_options("dynamic", "z:x,x:y");
  o.amplitude = 1e-4;
  const OscillatoryShearResult dynamic = run_oscillatory_shear(p, o);
  o.solver = "static";
  const OscillatoryShearResult quasi_static = run_oscillatory_shear(p, o);
  ASSERT_EQ(dynamic.runs.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k)
    EXPECT_NEAR(quasi_static.runs[k].storage_modulus, dynamic.runs[k].storage_modulus,
                0.02 * dynamic.runs[k].storage_modulus)
        << orientation_name(dynamic.runs[k].orientation);
}

TEST(StaticSolver, AgreesWithTheDynamicCompressionTestOnARandomBondedSample) {
  const Packing p = random_bonded_sample(300, 3);
  UniaxialCompressionSetup setup;
  setup.options.threads = 1;
  setup.options.max_strain = 0.05;
  setup.options.samples = 300;
  setup.finish(p);
  // Eq. 16 on compressed bonds too: the peak then lies near 2 % strain (with stretched bonds
  // only the sample still hardens at 5 %, and the "strength" would be the stress at max_strain).
  for (auto& b : setup.options.bond_materials) b.compressive_breakage = true;
  const UniaxialCompressionResult dynamic = run_uniaxial_compression(p, setup.options);
  setup.options.solver = "static";
  const UniaxialCompressionResult quasi_static = run_uniaxial_compression(p, setup.options);
  ASSERT_GT(dynamic.broken_bonds, 0u);
  ASSERT_GT(quasi_static.broken_bonds, 0u);
  EXPECT_NEAR(quasi_static.youngs_modulus, dynamic.youngs_modulus, 0.02 * dynamic.youngs_modulus);
  EXPECT_LT(dynamic.strain_at_peak, 0.8 * setup.options.max_strain);  // a peak, not the end of the run
  EXPECT_LT(quasi_static.strain_at_peak, 0.8 * setup.options.max_strain);
  EXPECT_NEAR(quasi_static.strength, dynamic.strength, 0.10 * dynamic.strength);
}

// Snapshots at applied stresses (Table 2's 31.3 MPa): on the elastic column a stress request is
// the strain request at stress / E, field for field; past the first break it lies on the first
// linear branch whose break load reaches it, carries the requested stress itself, and holds that
// branch's network (its broken bonds NaN in the bond strains). A stress the run never reaches gives no snapshot.
TEST(StaticSolver, StressSnapshotsLieOnTheFirstBranchThatCarriesTheirStress) {
  const Packing column = test::bonded_lattice(generate::LatticeType::sc, {3, 3, 8}, r, 1.75);
  UniaxialCompressionOptions o = compression_options("static");
  o.max_strain = 0.01;
  const double stress = 20e6, strain = stress / sc_modulus();
  o.snapshot_stresses = {stress};
  o.snapshot_strains = {strain};
  const UniaxialCompressionResult elastic = run_uniaxial_compression(column, o);
  ASSERT_EQ(elastic.snapshots.size(), 2u);
  // In the order of their strains: the measured E lies above the closed form in its last digits.
  const bool stress_first = std::isnan(elastic.snapshots[0].requested_strain);
  const UniaxialCompressionSnapshot& by_strain = elastic.snapshots[stress_first ? 1 : 0];
  const UniaxialCompressionSnapshot& by_stress = elastic.snapshots[stress_first ? 0 : 1];
  EXPECT_LE(elastic.snapshots[0].strain, elastic.snapshots[1].strain);
  EXPECT_EQ(by_strain.requested_strain, strain);
  EXPECT_TRUE(std::isnan(by_strain.requested_stress));
  EXPECT_EQ(by_stress.requested_stress, stress);
  EXPECT_TRUE(std::isnan(by_stress.requested_strain));
  EXPECT_NEAR(by_stress.stress, stress, 1e-12 * stress);
  EXPECT_NEAR(by_stress.strain, stress / elastic.youngs_modulus, 1e-12 * strain);
  EXPECT_NEAR(elastic.youngs_modulus, sc_modulus(), 1e-6 * sc_modulus());
  // Unsorted requests merge in the order of their strains: 0.5 and 2 x that strain around the stress.
  o.snapshot_strains = {2.0 * strain, 0.5 * strain};
  const UniaxialCompressionResult merged = run_uniaxial_compression(column, o);
  ASSERT_EQ(merged.snapshots.size(), 3u);
  EXPECT_EQ(merged.snapshots[0].requested_strain, 0.5 * strain);
  EXPECT_EQ(merged.snapshots[1].requested_stress, stress);
  EXPECT_EQ(merged.snapshots[2].requested_strain, 2.0 * strain);
  ASSERT_EQ(by_stress.particle_stress.size(), by_strain.particle_stress.size());
  for (std::size_t k = 0; k < by_stress.particle_stress.size(); ++k)
    EXPECT_NEAR(by_stress.particle_stress[k][8], by_strain.particle_stress[k][8],
                1e-6 * std::abs(by_strain.particle_stress[k][8]) + 1e-9 * stress);

  const Packing p = random_bonded_sample(300, 3);
  UniaxialCompressionSetup setup;
  setup.options.threads = 1;
  setup.options.max_strain = 0.05;
  setup.finish(p);
  setup.options.solver = "static";
  for (auto& b : setup.options.bond_materials) b.compressive_breakage = true;
  const UniaxialCompressionResult first = run_uniaxial_compression(p, setup.options);
  ASSERT_GT(first.broken_bonds, 10u);
  ASSERT_GE(first.curve.size(), 4u);
  // A load above the first break's and below the peak, and one above the peak.
  const double load = 0.5 * (first.curve[1].stress + first.strength);
  ASSERT_GT(load, first.curve[1].stress);
  setup.options.snapshot_stresses = {2.0 * first.strength, load};
  const UniaxialCompressionResult res = run_uniaxial_compression(p, setup.options);
  ASSERT_EQ(res.snapshots.size(), 1u);
  const UniaxialCompressionSnapshot& s = res.snapshots[0];
  EXPECT_EQ(s.requested_stress, load);
  EXPECT_NEAR(s.stress, load, 1e-12 * load);
  // Branch j (from the curve's point j - 1) ends at curve[j]: the first to reach the load.
  std::size_t j = 1;
  while (res.curve[j].stress < load) ++j;
  ASSERT_GT(j, 1u);
  EXPECT_LE(s.strain, res.curve[j].strain);
  EXPECT_GT(s.strain, 0.0);
  const auto broken = static_cast<std::size_t>(
      std::count_if(s.bond_strain.begin(), s.bond_strain.end(), [](double e) { return std::isnan(e); }));
  EXPECT_EQ(broken, res.curve[j - 1].broken_bonds);
  EXPECT_GT(res.curve[j - 1].broken_bonds, 0u);

  // A run that stops at max_breaks takes a strain it never reached on the last network it
  // solved: the breaks of its last point are not yet missing from it.
  setup.options.snapshot_stresses = {};
  setup.options.snapshot_strains = {0.04};
  setup.options.max_breaks = static_cast<long>(res.curve[j - 1].broken_bonds) + 1;
  const UniaxialCompressionResult stopped = run_uniaxial_compression(p, setup.options);
  ASSERT_EQ(stopped.snapshots.size(), 1u);
  ASSERT_GE(stopped.curve.size(), 2u);
  const auto& last = stopped.snapshots[0].bond_strain;
  EXPECT_EQ(static_cast<std::size_t>(std::count_if(last.begin(), last.end(), [](double e) { return std::isnan(e); })),
            stopped.curve[stopped.curve.size() - 2].broken_bonds);
  EXPECT_LT(stopped.curve[stopped.curve.size() - 2].broken_bonds, stopped.broken_bonds);
}

TEST(StaticSolver, BackendsAgree) {
  const std::vector<std::string> backends = static_solver_backends();
  if (backends.size() < 2) GTEST_SKIP() << "built without CHOLMOD";
  const Packing p = diluted_fcc(0.7);
  StaticSolverOptions a, b;
  a.backend = "cholmod";
  b.backend = "eigen";
  const PeriodicStiffness ca = periodic_stiffness(p, contact_bond_config(100.0, 10.0), a);
  const PeriodicStiffness cb = periodic_stiffness(p, contact_bond_config(100.0, 10.0), b);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(ca.stiffness[i][j], cb.stiffness[i][j], 1e-9 * ca.stiffness[0][0]);
  EXPECT_GT(ca.shear_modulus, 0.0);
}

// A 300-particle bonded sample set up for compression and linearized for the static solver,
// with the displacements of 0.1 % strain on its gripped particles.
struct LinearizedSample {
  UniaxialCompressionSpecimen specimen;
  StaticLinks links;
  std::vector<double> q0;
};
LinearizedSample linearized_sample(unsigned seed) {
  UniaxialCompressionOptions o = compression_options("static");
  UniaxialCompressionResult info;
  LinearizedSample out;
  out.specimen = prepare_uniaxial_compression(random_bonded_sample(300, seed), o, info);
  out.links = linearize_links(out.specimen.model, compression_engine_config(o));
  out.q0.assign(6 * out.specimen.model.size(), 0.0);
  for (std::size_t k = 0; k < out.specimen.model.size(); ++k)
    if (out.specimen.grip[k]) out.q0[6 * k + 2] = -1e-3 * info.height;
  return out;
}

// bench_static orderings (docs/static-solver.md): every ordering's factor holds at least the
// matrix's own lower triangle and at most a dense one, and CHOLMOD's default is one of those it
// tried, with that one's fill.
TEST(StaticSolver, OrderingFillNamesEachOrderingAndTheDefaultsChoice) {
  const LinearizedSample sample = linearized_sample(5);
  StiffnessAssembly a(sample.links, sample.specimen.model.fixed);
  a.assemble({}, 1e-12);
  const std::vector<OrderingFill> fills = ordering_fill(a);
  const std::vector<std::string> backends = static_solver_backends();
  if (std::find(backends.begin(), backends.end(), "cholmod") == backends.end()) {
    EXPECT_TRUE(fills.empty());
    GTEST_SKIP() << "built without CHOLMOD";
  }
  ASSERT_EQ(fills.size(), 6u);
  const double n = static_cast<double>(a.unknowns());
  for (const OrderingFill& f : fills) {
    EXPECT_GE(f.factor_nonzeros, static_cast<double>(a.values().size())) << f.name;
    EXPECT_LE(f.factor_nonzeros, n * (n + 1) / 2) << f.name;
    EXPECT_GT(f.flops, 0.0) << f.name;
  }
  EXPECT_EQ(fills[0].name, "AMD");
  EXPECT_EQ(fills[1].name, "METIS");
  EXPECT_EQ(fills[2].name, "NESDIS (CHOLMOD)");
  EXPECT_EQ(fills[4].name, "METIS on the particle graph");
  EXPECT_EQ(fills[5].name, "NESDIS on the particle graph");
  const std::string& chosen = fills[3].name;
  ASSERT_TRUE(chosen.starts_with("default (") && chosen.ends_with(")")) << chosen;
  const std::string inner = chosen.substr(9, chosen.size() - 10);
  const auto same =
      std::find_if(fills.begin(), fills.begin() + 3, [&](const OrderingFill& f) { return f.name == inner; });
  ASSERT_NE(same, fills.begin() + 3) << chosen;
  EXPECT_EQ(fills[3].factor_nonzeros, same->factor_nonzeros);
}

// Links switched off after the factorization: the downdated factor (CHOLMOD) and the
// preconditioned conjugate gradients with the old factor (Eigen, or modify_factor off) give the
// solution of a fresh factorization, and the links' forces (what the failure criteria read) agree.
TEST(StaticSolver, ResolveAfterRemovingLinksEqualsAFreshFactorization) {
  const LinearizedSample sample = linearized_sample(5);
  const UniaxialCompressionSpecimen& s = sample.specimen;
  const StaticLinks& links = sample.links;
  const std::vector<double>& q0 = sample.q0;
  ASSERT_GT(links.bonds(), 100u);
  auto switched_off = [](std::size_t k) { return k % 17 == 0 || k % 29 == 3; };
  StaticSolver fresh(links, s.model.fixed, {});
  for (std::size_t k = 0; k < links.size(); ++k)
    if (switched_off(k)) fresh.deactivate(k);
  std::vector<double> q_fresh = q0;
  fresh.solve(q_fresh, {});
  const dem::ContactForces forces_fresh = link_forces(links, q_fresh, {}, fresh.active_links());
  double force_scale = 0.0;
  for (const Vec3& f : forces_fresh.force) force_scale = std::max(force_scale, norm(f));
  ASSERT_GT(force_scale, 0.0);

  for (const std::string& backend : static_solver_backends())
    for (const bool modify : {true, false}) {
      SCOPED_TRACE(backend + (modify ? " downdate" : " pcg"));
      StaticSolverOptions so;
      so.backend = backend;
      so.modify_factor = modify;
      StaticSolver reused(links, s.model.fixed, so);
      std::vector<double> q = q0;
      reused.solve(q, {});
      // One at a time, each followed by a solve, as the sequential linear analysis does.
      long off = 0;
      for (std::size_t k = 0; k < links.size(); ++k)
        if (switched_off(k)) {
          reused.deactivate(k);
          ++off;
          if (off % 8 == 0) {
            q = q0;
            reused.solve(q, {});
          }
        }
      q = q0;
      reused.solve(q, {});
      const auto& st = reused.stats();
      const bool downdates = modify && backend == "cholmod";
      EXPECT_EQ(st.downdates, downdates ? off : 0);
      // The downdated factor solves to the tolerance by itself (a downdate of the unscaled
      // link stiffness lost its rotational part and needed three iterations per solve).
      if (downdates) {
        EXPECT_EQ(st.pcg_iterations, 0);
        // Every re-solve after the first is the backward sweep from the forward half carried
        // through the downdates, the links' pull on the plate included.
        EXPECT_EQ(st.backward_only_solves, st.solves - 1);
      } else {
        EXPECT_GT(st.pcg_iterations, 0);
      }
      EXPECT_LE(st.factorizations, downdates ? 1 : 3);
      const dem::ContactForces forces = link_forces(links, q, {}, reused.active_links());
      ASSERT_EQ(forces.force.size(), forces_fresh.force.size());
      double diff = 0.0;
      for (std::size_t k = 0; k < forces.force.size(); ++k)
        diff = std::max(diff, norm(forces.force[k] - forces_fresh.force[k]));
      EXPECT_LT(diff, 1e-8 * force_scale);
    }
}

// Checking only every 16th re-solve of the sequential linear analysis changes nothing while the
// checks pass (the unchecked solves are the checked ones: a passed check leaves the solution as
// it is), and when a check fails the analysis goes back to the last checked break and redoes the
// breaks since with a fresh factorization: the same breaks at the same strains, the curve
// without duplicated points. The failing checks are forced by a tolerance no solve can reach
// (each check then refines, gives up and factorizes anew).
TEST(StaticSolver, SequentialLinearAnalysisWithSparseChecksRollsBackWhenACheckFails) {
  if (static_solver_backends().front() != "cholmod") GTEST_SKIP() << "built without CHOLMOD";
  const Packing p = random_bonded_sample(300, 3);
  UniaxialCompressionSetup setup = static_compression_to_five_percent(p);
  setup.options.check_interval = 1;
  const UniaxialCompressionResult each = run_uniaxial_compression(p, setup.options);
  ASSERT_GT(each.broken_bonds, 40u);
  EXPECT_EQ(each.rollbacks, 0);
  EXPECT_EQ(each.checks, each.downdates > 0 ? static_cast<long>(each.solves) - 1 : 0);
  auto same_analysis = [&](const UniaxialCompressionResult& r, double tolerance) {
    ASSERT_EQ(r.breaks.size(), each.breaks.size());
    for (std::size_t k = 0; k < r.breaks.size(); ++k) {
      EXPECT_EQ(r.breaks[k].bond, each.breaks[k].bond) << "break " << k;
      EXPECT_NEAR(r.break_strain[k], each.break_strain[k], tolerance * each.break_strain[k]) << "break " << k;
    }
    ASSERT_EQ(r.curve.size(), each.curve.size());
    for (std::size_t k = 0; k < r.curve.size(); ++k) {
      EXPECT_EQ(r.curve[k].broken_bonds, each.curve[k].broken_bonds) << "point " << k;
      EXPECT_NEAR(r.curve[k].stress, each.curve[k].stress, tolerance * each.strength) << "point " << k;
    }
    EXPECT_EQ(r.stop_reason, each.stop_reason);
    EXPECT_NEAR(r.strength, each.strength, tolerance * each.strength);
    for (std::size_t b = 0; b < r.model.bonds.size(); ++b) EXPECT_EQ(r.model.bonds.state[b], each.model.bonds.state[b]);
  };
  // Snapshots on the way (a rollback takes back the ones it undoes, and their counters): two
  // stresses between the first break and the peak, a strain before the peak and one past the
  // end, against those of the run that checks every re-solve.
  setup.options.snapshot_stresses = {0.9 * each.strength, 0.5 * (each.curve[1].stress + each.strength)};
  setup.options.snapshot_strains = {0.5 * each.strain_at_peak, setup.options.max_strain};
  const UniaxialCompressionResult each_snapshots = run_uniaxial_compression(p, setup.options);
  ASSERT_EQ(each_snapshots.snapshots.size(), 4u);
  auto same_snapshots = [&](const UniaxialCompressionResult& r, double tolerance) {
    ASSERT_EQ(r.snapshots.size(), each_snapshots.snapshots.size());
    for (std::size_t k = 0; k < r.snapshots.size(); ++k) {
      const UniaxialCompressionSnapshot &a = r.snapshots[k], &b = each_snapshots.snapshots[k];
      EXPECT_EQ(std::isnan(a.requested_stress), std::isnan(b.requested_stress)) << "snapshot " << k;
      EXPECT_NEAR(a.strain, b.strain, tolerance * b.strain) << "snapshot " << k;
      ASSERT_EQ(a.bond_strain.size(), b.bond_strain.size());
      for (std::size_t j = 0; j < a.bond_strain.size(); ++j)
        EXPECT_EQ(std::isnan(a.bond_strain[j]), std::isnan(b.bond_strain[j])) << "snapshot " << k << " bond " << j;
    }
  };
  setup.options.check_interval = 16;
  const UniaxialCompressionResult sparse = run_uniaxial_compression(p, setup.options);
  same_analysis(sparse, 0.0);
  same_snapshots(sparse, 0.0);
  EXPECT_EQ(sparse.rollbacks, 0);
  EXPECT_LT(sparse.checks, each.checks / 8);
  EXPECT_GT(sparse.checks, 0);

  setup.options.check_tolerance = 1e-30;
  const UniaxialCompressionResult rolled_back = run_uniaxial_compression(p, setup.options);
  same_analysis(rolled_back, 1e-9);
  same_snapshots(rolled_back, 1e-9);
  EXPECT_GT(rolled_back.rollbacks, 2);
  EXPECT_GT(rolled_back.factorizations, static_cast<std::size_t>(rolled_back.rollbacks));
}

// The stop past the peak (stop_drop). Each break of the sequential linear analysis takes a link
// out of a linear network, so the stress at unit strain never rises: once max_strain times it
// is below stop_drop x peak no later point can come back above that, and the run stops there
// instead of following a snap-back (breaks at falling strains) below the peak's strain. Against
// the run to max_strain (stop_drop 0): its stress per unit strain falls at every break (the
// bound), and for each stop_drop the stopped run is that run's first points, with the same peak,
// strain at peak and E, ending at the first break where either rule holds (predicted from the
// full curve). Both rules end some of the runs.
TEST(StaticSolver, StopDropEndsTheRunWhereNoLaterPointCanComeBackAboveIt) {
  const Packing p = random_bonded_sample(300, 3);
  UniaxialCompressionSetup setup = static_compression_to_five_percent(p);
  setup.options.stop_drop = 0.0;
  const UniaxialCompressionResult full = run_uniaxial_compression(p, setup.options);
  const std::vector<UniaxialCompressionPoint>& curve = full.curve;
  ASSERT_GT(curve.size(), 50u);
  // Point k >= 1 lies on the network after k - 1 break events: its stress per unit strain.
  auto per_strain = [&](std::size_t k) { return curve[k].stress / curve[k].strain; };
  for (std::size_t k = 2; k < curve.size(); ++k) EXPECT_LE(per_strain(k), per_strain(k - 1) * (1 + 1e-9)) << k;
  int by_drop = 0, by_bound = 0;
  for (double stop_drop : {0.3, 0.5, 0.7, 0.85, 0.95}) {
    // The loop's step i (i >= 1 break events) tests the network after them against the last
    // break's strain (point i) and the peak of points 1..i.
    double peak = 0.0, strain_at_peak = 0.0;
    std::size_t stop = 0;
    bool bound = false;
    for (std::size_t i = 1; i + 1 < curve.size() && stop == 0; ++i) {
      if (curve[i].stress > peak) peak = curve[i].stress, strain_at_peak = curve[i].strain;
      const double stress1 = per_strain(i + 1), strain = curve[i].strain;
      const bool dropped = strain >= strain_at_peak && strain * stress1 < stop_drop * peak;
      bound = !dropped && setup.options.max_strain * stress1 < stop_drop * peak;
      if (dropped || bound) stop = i;
    }
    ASSERT_GT(stop, 0u) << stop_drop;
    (bound ? by_bound : by_drop) += 1;
    setup.options.stop_drop = stop_drop;
    const UniaxialCompressionResult stopped = run_uniaxial_compression(p, setup.options);
    EXPECT_EQ(stopped.strength, full.strength) << stop_drop;
    EXPECT_EQ(stopped.strain_at_peak, full.strain_at_peak) << stop_drop;
    EXPECT_EQ(stopped.youngs_modulus, full.youngs_modulus) << stop_drop;
    ASSERT_EQ(stopped.curve.size(), stop + 2) << stop_drop;
    for (std::size_t k = 0; k <= stop; ++k)
      EXPECT_EQ(stopped.curve[k].stress, curve[k].stress) << stop_drop << " " << k;
    EXPECT_EQ(stopped.curve.back().strain, curve[stop].strain);
    EXPECT_DOUBLE_EQ(stopped.curve.back().stress, curve[stop].strain * per_strain(stop + 1));
    EXPECT_EQ(stopped.broken_bonds, curve[stop].broken_bonds);
    EXPECT_NE(stopped.stop_reason.find(bound ? "up to max_strain" : "after the peak"), std::string::npos)
        << stop_drop << ": " << stopped.stop_reason;
  }
  EXPECT_GT(by_drop, 0);
  EXPECT_GT(by_bound, 0);
}

TEST(StaticSolver, EnergyCheckOfADowndatedFactorEqualsThatOfAFreshFactorization) {
  // The refinement's energy check r^T K^-1 r takes the forward half of a solve on CHOLMOD's
  // factors (LL^T fresh, LDL^T after downdates): against Eigen's full solve on the same links.
  if (static_solver_backends().front() != "cholmod") GTEST_SKIP() << "built without CHOLMOD";
  const LinearizedSample sample = linearized_sample(7);
  const UniaxialCompressionSpecimen& s = sample.specimen;
  const StaticLinks& links = sample.links;
  const std::vector<double>& q0 = sample.q0;
  StaticSolverOptions eigen_options;
  eigen_options.backend = "eigen";
  StaticSolver cholmod(links, s.model.fixed, {});
  std::vector<double> q = q0;
  cholmod.solve(q, {});
  Random rng(11);
  std::vector<double> residual(cholmod.stats().unknowns);
  // Rotations and translations differ by ~r^2 in stiffness: a residual of both kinds.
  for (double& v : residual) v = rng.uniform(-1.0, 1.0);
  for (const bool downdated : {false, true}) {
    SCOPED_TRACE(downdated ? "after downdates (simplicial LDL^T)" : "fresh (supernodal LL^T)");
    if (downdated) {
      for (std::size_t k = 0; k < links.size(); k += 13) cholmod.deactivate(k);
      q = q0;
      cholmod.solve(q, {});
      ASSERT_GT(cholmod.stats().downdates, 0);
    }
    StaticSolver eigen(links, s.model.fixed, eigen_options);
    for (std::size_t k = 0; k < links.size(); ++k)
      if (!cholmod.active(k)) eigen.deactivate(k);
    std::vector<double> qe = q0;
    eigen.solve(qe, {});
    const double expected = eigen.inverse_norm_squared(residual);
    ASSERT_GT(expected, 0.0);
    EXPECT_NEAR(cholmod.inverse_norm_squared(residual), expected, 1e-8 * expected);
  }
}

// An unbonded contact enters the linearization sticking (its shear spring below the Coulomb
// limit), except without friction, where the engine's contact carries no shear force: two
// overlapping spheres, each contact law, friction 0 and 0.3.
TEST(StaticSolver, AFrictionlessContactHasNoShearStiffness) {
  Packing p;
  p.box.length = {1e-5, 1e-5, 1e-5};
  p.box.periodic = {false, false, false};
  p.add({4e-6, 5e-6, 5e-6}, r0, 0);
  p.add({4e-6 + 2 * r0 * (1 - 1e-3), 5e-6, 5e-6}, r0, 0);
  for (const std::string law : {"linear", "hertz_mindlin"})
    for (const double friction : {0.0, 0.3}) {
      SCOPED_TRACE(law + " friction " + std::to_string(friction));
      dem::EngineConfig c;
      c.contact_law = law;
      c.types = {dem::Material{
          .normal_stiffness = 100.0, .shear_stiffness = 10.0, .friction = friction, .youngs_modulus = 1e9}};
      const StaticLinks links = linearize_links(p, c);
      ASSERT_EQ(links.size(), 1u);
      EXPECT_GT(links.stiffness[0].normal, 0.0);
      if (friction > 0.0)
        EXPECT_GT(links.stiffness[0].shear, 0.05 * links.stiffness[0].normal);
      else
        EXPECT_EQ(links.stiffness[0].shear, 0.0);
    }
}

// A frictionless contact in a direction off the axes: its rotation entries are exactly zero,
// not the rounding of k_n b^2 (n x theta) . n, which the diagonal shift would take for a
// stiffness (an N = 8000 BD gel failed as not positive definite), and the particle it touches
// alone gets a positive definite matrix from the shift.
TEST(StaticSolver, AFrictionlessContactLeavesNoRoundingOnTheRotations) {
  Packing p;
  p.box.length = {1e-5, 1e-5, 1e-5};
  p.box.periodic = {false, false, false};
  const Vec3 n = Vec3{0.37, -0.61, 0.70} * (1.0 / norm(Vec3{0.37, -0.61, 0.70}));
  p.add({5e-6, 5e-6, 5e-6}, r0, 0);
  p.add(Vec3{5e-6, 5e-6, 5e-6} + (2 * r0 * (1 - 1e-3)) * n, r0, 0);
  dem::EngineConfig c;
  c.contact_law = "linear";
  c.types = {dem::Material{.normal_stiffness = 100.0, .shear_stiffness = 10.0, .friction = 0.0}};
  const StaticLinks links = linearize_links(p, c);
  ASSERT_EQ(links.size(), 1u);
  const auto blocks = link_stiffness(links, 0);
  for (const auto& K : blocks)
    for (int r = 0; r < 6; ++r)
      for (int col = 0; col < 6; ++col)
        if (r >= 3 || col >= 3) {
          EXPECT_EQ(K[static_cast<std::size_t>(6 * r + col)], 0.0) << r << "," << col;
        }
  EXPECT_GT(blocks[0][0], 0.0);
  // Particle 0 held by the contact alone (particle 1 prescribed): the shift makes its rotations
  // positive definite, and the factorization succeeds.
  const std::vector<std::uint8_t> prescribed = {0, 1};
  StaticSolver solver(links, prescribed, StaticSolverOptions{});
  std::vector<double> q(12, 0.0);
  q[6] = 1e-9;
  ASSERT_NO_THROW(solver.solve(q, DisplacementGradient{}));
  // Particle 0 follows along n (the contact carries no force) and does not turn.
  EXPECT_NEAR(link_response(links, 0, q, DisplacementGradient{}).normal_displacement, 0.0, 1e-9 * 1e-9);
  EXPECT_NEAR(dot(Vec3{q[0], q[1], q[2]}, n), 1e-9 * n.x, 1e-9 * 1e-9);
  for (std::size_t u = 3; u < 6; ++u) EXPECT_LT(std::abs(q[u]) * r0, 1e-9 * 1e-9);
}

TEST(StaticSolver, BadInputIsAnInputError) {
  const Packing column = test::bonded_lattice(generate::LatticeType::sc, {3, 3, 4}, r, 1.01);
  UniaxialCompressionOptions o = compression_options("static");
  o.plate = "contact";
  EXPECT_THROW(run_uniaxial_compression(column, o), InputError);
  o = compression_options("quasi");
  EXPECT_THROW(run_uniaxial_compression(column, o), InputError);
  o = compression_options("static");
  o.solver_backend = "superlu";  // no such backend
  EXPECT_THROW(run_uniaxial_compression(column, o), InputError);
#ifndef PACKLAB_HAVE_PETSC
  o.solver_backend = "petsc";  // only in a build with PETSc
  EXPECT_THROW(run_uniaxial_compression(column, o), InputError);
#endif
  const Packing sc = test::bonded_lattice(generate::LatticeType::sc, {3, 3, 3}, r0, 1.01);
  EXPECT_THROW(run_oscillatory_shear(sc, shear_options("implicit")), InputError);
  // A contact law without a linearization, with touching unbonded pairs.
  dem::EngineConfig c = contact_bond_config(100.0, 10.0);
  c.contact_law = "linear_adhesive";
  Packing unbonded = sc;
  unbonded.bonds = Bonds{};
  EXPECT_THROW(periodic_stiffness(unbonded, c), InputError);
  Packing open = sc;
  open.box.periodic = {true, true, false};
  EXPECT_THROW(periodic_stiffness(open, contact_bond_config(100.0, 10.0)), InputError);
}
