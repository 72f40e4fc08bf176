// Oscillatory shear test (doh-elastic-properties §2.4): set-up, cycle evaluation, the closed
// form of a simple-cubic network of contact bonds between rigid plates, linearity in k_n,
// quasi-static rate independence and phase angle, orientation symmetry, calibration.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/generate/lattice.hpp"
#include "packlab/mechanics/oscillatory_shear.hpp"
#include "packlab/mechanics/shear_calibration.hpp"
#include "../test_packings.hpp"

using namespace packlab;
using namespace packlab::mechanics;

namespace {

constexpr double r0 = 0.25e-6;

// Contact bonds (cutoff 1.01 d) between the touching neighbours of a cubic lattice.
Packing bonded_lattice(generate::LatticeType type, int cells) {
  return test::bonded_lattice(type, {cells, cells, cells}, r0, 1.01);
}

// An FCC network with a deterministic fraction of its bonds removed: disordered, non-affine.
Packing diluted_fcc(double keep) {
  Packing p = bonded_lattice(generate::LatticeType::fcc, 3);
  Bonds kept;
  Random rng(7);
  for (std::size_t b = 0; b < p.bonds.size(); ++b)
    if (rng.uniform() < keep) kept.add(p.bonds.i[b], p.bonds.j[b], p.bonds.image[b], 0, p.bonds.rest_length[b]);
  p.bonds = kept;
  return p;
}

OscillatoryShearOptions quick_options(int cycles = 3, const std::string& orientations = "z:x") {
  OscillatoryShearOptions o;
  o.stiffness_rule = "contact";
  o.normal_stiffness = 100.0;
  o.shear_stiffness = 10.0;
  o.normal_strength = o.shear_strength = std::numeric_limits<double>::infinity();
  o.cycles = cycles;
  o.steps_per_cycle = 4000;
  o.samples_per_cycle = 40;
  o.orientations = orientations;
  o.threads = 1;
  return o;
}

}  // namespace

TEST(OscillatoryShear, OrientationSpecs) {
  EXPECT_EQ(shear_orientations("all").size(), 6u);
  const auto z = shear_orientations("z");
  ASSERT_EQ(z.size(), 2u);
  EXPECT_EQ(orientation_name(z[0]), "z:x");
  EXPECT_EQ(orientation_name(z[1]), "z:y");
  const auto pairs = shear_orientations("x:y, y:z");
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[1].normal, 1);
  EXPECT_EQ(pairs[1].direction, 2);
  EXPECT_THROW(shear_orientations("w"), InputError);
  EXPECT_THROW(shear_orientations("z:z"), InputError);
  OscillatoryShearOptions o;
  o.steps_per_cycle = 1001;
  EXPECT_THROW(validate(o), InputError);
}

TEST(OscillatoryShear, EvaluateCycleRecoversModulusAndPhaseOfSyntheticSignals) {
  const double g0 = 1e-3, modulus = 2.5e6, delta = 0.1, offset = 40.0;
  std::vector<ShearSample> samples;
  for (int k = 1; k <= 40; ++k) {
    ShearSample s;
    s.cycle = 2;
    s.phase = 2.0 * std::numbers::pi * k / 40.0;
    s.strain = g0 * std::sin(s.phase);
    s.stress = offset + modulus * g0 * std::sin(s.phase + delta);
    s.plate_stress = s.stress;
    samples.push_back(s);
  }
  const ShearCycle c = evaluate_cycle(samples, 2);
  EXPECT_NEAR(c.phase_angle, delta, 1e-12);
  // Peak-to-peak of 40 samples of a shifted sine: the sampled peaks miss the true ones by at
  // most 1 - cos(pi/40).
  EXPECT_NEAR(c.complex_modulus, modulus, modulus * (1.0 - std::cos(std::numbers::pi / 40.0)));
  EXPECT_NEAR(c.storage_modulus, c.complex_modulus * std::cos(delta), 1e-9 * modulus);
  EXPECT_DOUBLE_EQ(evaluate_cycle(samples, 1).storage_modulus, 0.0);  // no samples of cycle 1
}

TEST(OscillatoryShear, SetupHasPlatesFromThePeriodicImagesAndBondsAcrossTheBoundary) {
  const Packing sc = bonded_lattice(generate::LatticeType::sc, 4);  // 64 particles, 192 bonds
  ASSERT_EQ(sc.bonds.size(), 192u);
  const ShearSetup s = build_shear_setup(oriented_packing(sc, {2, 0}), 3, 1);
  EXPECT_EQ(s.structure, 64u);
  EXPECT_EQ(s.lower, 48u);  // three layers of 16
  EXPECT_EQ(s.upper, 48u);
  EXPECT_FALSE(s.packing.box.periodic[2]);
  EXPECT_TRUE(s.packing.box.periodic[0] && s.packing.box.periodic[1]);
  // 192 bonds: 128 in-plane and 48 vertical inside the structure, 16 crossing z each bonding
  // the top layer to the upper plate and the bottom layer to the lower plate (2 x 16).
  EXPECT_EQ(s.packing.bonds.size(), 128u + 48u + 32u);
  for (std::size_t b = 0; b < s.packing.bonds.size(); ++b) {
    const auto i = static_cast<std::size_t>(s.packing.bonds.i[b]), j = static_cast<std::size_t>(s.packing.bonds.j[b]);
    EXPECT_FALSE(s.role[i] != 0 && s.role[j] != 0);
    const Vec3 d = s.packing.position[j] + s.packing.box.shift_vector(s.packing.bonds.image[b]) - s.packing.position[i];
    EXPECT_NEAR(norm(d), 2.0 * r0, 1e-9 * r0);
  }
  for (std::size_t k = 0; k < s.packing.size(); ++k) EXPECT_EQ(s.packing.fixed[k] != 0, s.role[k] != 0);
  EXPECT_DOUBLE_EQ(s.height, 4 * 2 * r0);
}

// Simple-cubic network of contact bonds (spacing d = 2r, contact stiffness k_s) between rigid,
// non-rotating plates. Simple shear of n layers by a plate deflection U: every vertical bond
// carries the same shear force f; torque balance of a particle (two vertical bonds with lever r,
// four in-layer bonds along x turned by its rotation theta: -4 k_s r^2 theta) gives
// theta = f / (2 k_s r) in every layer and zero in the plates; summing the bond shear
// displacements u_{k+1} - u_k - r (theta_k + theta_{k+1}) over the n + 1 vertical bonds,
// (n + 1) f / k_s = U - n f / k_s, so f = k_s U / (2n + 1) and, with sigma = f / d^2 and
// gamma = U / (n d):  G = k_s n / ((2n + 1) d)  (bulk limit k_s / (2d); k_n plays no part).
TEST(OscillatoryShear, SimpleCubicNetworkMatchesTheSpringNetworkClosedForm) {
  const Packing sc = bonded_lattice(generate::LatticeType::sc, 4);
  OscillatoryShearOptions o = quick_options(1, "all");
  o.regions = 1;
  o.steps_per_cycle = 16000;  // 4000 leaves the plate force ringing by a few per cent
  const OscillatoryShearResult r = run_oscillatory_shear(sc, o);
  const double d = 2.0 * r0, n = 4.0;
  const double expected = o.shear_stiffness * n / ((2.0 * n + 1.0) * d);
  ASSERT_EQ(r.runs.size(), 6u);
  for (const auto& run : r.runs) {
    EXPECT_NEAR(run.storage_modulus, expected, 0.01 * expected) << orientation_name(run.orientation);
    EXPECT_NEAR(run.plate_storage_modulus, expected, 0.01 * expected) << orientation_name(run.orientation);
    EXPECT_LT(std::abs(run.phase_angle), 0.01);
    EXPECT_EQ(run.broken_bonds, 0u);
  }
  EXPECT_LT(r.storage_modulus_std, 1e-3 * expected);  // cubic symmetry: the six agree
  // Under the particle rule the same numbers are particle stiffnesses: springs in series, k/2.
  o.stiffness_rule = "particle";
  o.orientations = "z:x";
  const OscillatoryShearResult half = run_oscillatory_shear(sc, o);
  EXPECT_NEAR(half.storage_modulus_mean, 0.5 * expected, 0.01 * expected);
}

TEST(OscillatoryShear, StorageModulusIsLinearInTheStiffnessAtAFixedRatio) {
  // Fig. 5: G' proportional to k_n at k_n / k_s = 10. Four times both stiffnesses quarters the
  // squared time step (dt halves, exactly in floating point), so the run is the same in steps,
  // every displacement the same and every force four times larger: G' x 4 to round-off.
  const Packing p = diluted_fcc(0.7);
  OscillatoryShearOptions o = quick_options(2);
  const OscillatoryShearResult a = run_oscillatory_shear(p, o);
  o.normal_stiffness *= 4.0;
  o.shear_stiffness *= 4.0;
  const OscillatoryShearResult b = run_oscillatory_shear(p, o);
  ASSERT_GT(a.storage_modulus_mean, 0.0);
  EXPECT_NEAR(b.storage_modulus_mean, 4.0 * a.storage_modulus_mean, 1e-12 * a.storage_modulus_mean);
  // And G' depends on k_n at fixed k_s in this non-affine network (unlike the cubic one).
  o.shear_stiffness /= 4.0;
  const OscillatoryShearResult c = run_oscillatory_shear(p, o);
  EXPECT_GT(c.storage_modulus_mean, 1.05 * a.storage_modulus_mean);
}

TEST(OscillatoryShear, QuasiStaticSlowerCycleGivesTheSameModulusAndNoPhaseLag) {
  const Packing p = diluted_fcc(0.7);
  OscillatoryShearOptions o = quick_options(2);
  const OscillatoryShearResult fast = run_oscillatory_shear(p, o);
  o.steps_per_cycle *= 2;
  const OscillatoryShearResult slow = run_oscillatory_shear(p, o);
  EXPECT_NEAR(slow.storage_modulus_mean, fast.storage_modulus_mean, 0.01 * slow.storage_modulus_mean);
  EXPECT_LT(std::abs(slow.phase_angle_mean), 0.01);
  EXPECT_LT(slow.phase_angle_max, 0.02);
  // A cycle far too short for the structure to follow lags and reads differently.
  o.steps_per_cycle = 80;
  o.samples_per_cycle = 40;
  const OscillatoryShearResult rushed = run_oscillatory_shear(p, o);
  EXPECT_GT(std::abs(rushed.phase_angle_mean), 0.05);
}

TEST(OscillatoryShear, CalibrationFindsTheNormalStiffnessOfATargetModulus) {
  const Packing p = diluted_fcc(0.7);
  OscillatoryShearOptions o = quick_options(1);
  o.normal_stiffness = 100.0;
  const double g100 = run_oscillatory_shear(p, o).storage_modulus_mean;
  const double target = 1.37 * g100;  // G' linear in k_n: the answer is k_n = 137 N/m
  const ShearCalibrationResult c = calibrate_normal_stiffness(p, target, o, 0.001);
  EXPECT_TRUE(c.converged) << c.reason;
  EXPECT_NEAR(c.normal_stiffness, 137.0, 0.002 * 137.0);
  EXPECT_NEAR(c.shear_stiffness, 13.7, 0.002 * 13.7);
  EXPECT_LE(c.evaluations, 4);
}

TEST(OscillatoryShear, RejectsUnbondedOrNonPeriodicPackings) {
  Packing p = bonded_lattice(generate::LatticeType::sc, 3);
  OscillatoryShearOptions o = quick_options();
  Packing open = p;
  open.box.periodic[2] = false;
  EXPECT_THROW(run_oscillatory_shear(open, o), InputError);
  Packing unbonded = p;
  unbonded.bonds = Bonds{};
  EXPECT_THROW(run_oscillatory_shear(unbonded, o), InputError);
}
