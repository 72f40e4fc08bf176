// Uniaxial compression (mechanics/uniaxial_compression): a lattice column of elastic bonds against its
// closed-form modulus, rate independence on a disordered sample, bad options. The modulus fit
// and the per-type stress statistics: tests/analyze/test_stress_strain.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "../test_packings.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/generate/lattice.hpp"
#include "packlab/mechanics/opal_materials.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"
#include "silica_compression.hpp"

using namespace packlab;
using namespace packlab::mechanics;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double r = 7.5e-9;  // the paper's 15 nm particles
constexpr double E = 6.53e9, nu = 0.17;

UniaxialCompressionOptions options(double strength = inf) { return test::silica_compression_options(E, nu, strength); }

// Simple cubic column, 3 x 3 cells across (periodic), `layers` levels, elastic bonds 1.75 d.
Packing sc_column(int layers) { return test::bonded_lattice(generate::LatticeType::sc, {3, 3, layers}, r, 1.75); }

// The test set-up of a pore-free force-biased packing (porosity 0.38, the paper's bulk sample;
// 400 particles, periodic x, y), elastic bonds 1.75 d, breakable silica bonds, at the automatic
// rate (1e-4 strain per elastic-wave transit, the command line's default) to 5 % strain.
UniaxialCompressionSetup bulk_sample_setup(const Packing& sample) {
  UniaxialCompressionSetup setup;
  setup.options.threads = 1;
  setup.options.max_strain = 0.05;
  setup.options.samples = 300;
  setup.finish(sample);
  return setup;
}

}  // namespace

// Periodic sides keep every level of a simple cubic column a rigid plane: the column is a chain
// of layer gaps, each crossed per particle by 1 axial (L0 = d), 4 face-diagonal (sqrt 2 d) and 4
// body-diagonal (sqrt 3 d) bonds. A gap closing by delta shortens a bond of direction n by
// delta n_z and shears it by delta sqrt(1 - n_z^2): z force (A / L0)(E n_z^2 + G (1 - n_z^2))
// delta (eq. 11), so the constrained modulus is
//   M = pi/4 [E + sqrt2 (E + G) + 4 (E + 2G) / (3 sqrt3)],  G = E / (2 (1 + nu)).
double sc_modulus() {
  const double G = E / (2 * (1 + nu));
  return std::numbers::pi / 4 * (E + std::sqrt(2.0) * (E + G) + 4 * (E + 2 * G) / (3 * std::sqrt(3.0)));
}

TEST(UniaxialCompression, GluedPlateOnASimpleCubicColumnGivesTheClosedFormModulus) {
  // Two fixed substrate levels, two glued levels moving with the plate: the gauge length is the
  // five gaps between them and the measured modulus is M itself. (At 1e6 1/s the start-up
  // waves of the plate are damped out before the linear fit; at 2e6 1/s they add 0.4 %.)
  const int layers = 8;
  UniaxialCompressionOptions o = options();
  o.max_strain = 0.003;
  o.strain_rate = 1e6;
  o.samples = 50;
  const UniaxialCompressionResult res = run_uniaxial_compression(sc_column(layers), o);
  EXPECT_EQ(res.fixed_particles, 18u);
  EXPECT_EQ(res.glued_particles, 18u);
  EXPECT_EQ(res.broken_bonds, 0u);
  EXPECT_NEAR(res.height, 5 * 2 * r, 1e-9 * r);
  EXPECT_NEAR(res.area, 9 * 4 * r * r, 1e-9 * r * r);
  ASSERT_TRUE(res.modulus.found);
  EXPECT_NEAR(res.youngs_modulus, sc_modulus(), 2e-3 * sc_modulus());
  const UniaxialCompressionPoint& last = res.curve.back();
  EXPECT_NEAR(last.stress, sc_modulus() * last.strain, 2e-3 * last.stress);
  EXPECT_LT(res.max_kinetic_ratio, 0.01);  // quasi-static
}

TEST(UniaxialCompression, ContactPlateAddsTheHertzCompliance) {
  // The paper's plate: a Hertz contact on each top particle carrying f = sigma d^2,
  // delta_H = (3 f / (4 E* sqrt r))^(2/3), E* = E / (2 (1 - nu^2)), in series with the N - 2
  // deforming gaps above the two fixed levels: plate displacement = delta_H + (N - 2) sigma d / M.
  const int layers = 8;
  UniaxialCompressionOptions o = options();
  o.plate = "contact";
  o.max_strain = 0.003;
  o.strain_rate = 2e6;
  o.samples = 50;
  const UniaxialCompressionResult res = run_uniaxial_compression(sc_column(layers), o);
  const double d = 2 * r, M = sc_modulus();
  const double e_star = E / (2 * (1 - nu * nu));
  ASSERT_GT(res.curve.size(), 10u);
  EXPECT_NEAR(res.height, layers * d, 1e-9 * d);
  for (std::size_t k : {res.curve.size() / 2, res.curve.size() - 1}) {
    const UniaxialCompressionPoint& p = res.curve[k];
    ASSERT_GT(p.stress, 0.0);
    const double f = p.stress * d * d;
    const double hertz = std::pow(3 * f / (4 * e_star * std::sqrt(r)), 2.0 / 3.0);
    const double predicted = hertz + (layers - 2) * p.stress * d / M;
    EXPECT_NEAR(p.displacement, predicted, 0.01 * predicted) << "point " << k << " strain " << p.strain;
  }
  // The tangent modulus H0 d(sigma)/d(delta) = H0 / (2/3 delta_H / sigma + (N - 2) d / M) grows
  // with the load; the fit over the top quarter of the stress lies between its values there.
  auto tangent = [&](double sigma) {
    const double hertz = std::pow(3 * sigma * d * d / (4 * e_star * std::sqrt(r)), 2.0 / 3.0);
    return res.height / (2.0 / 3.0 * hertz / sigma + (layers - 2) * d / M);
  };
  const double peak = res.curve.back().stress;
  EXPECT_GT(res.youngs_modulus, 0.99 * tangent((1 - o.modulus_window) * peak));
  EXPECT_LT(res.youngs_modulus, 1.01 * tangent(peak));
}

TEST(UniaxialCompression, HalvingTheStrainRateChangesNeitherModulusNorStrength) {
  // The bulk sample compressed past its peak at the automatic rate and at half that: E within
  // 0.2 %, strength within 5 %.
  const Packing p = test::random_bonded_sample(400, 3, r);
  UniaxialCompressionSetup setup = bulk_sample_setup(p);
  const double rate = setup.options.strain_rate;
  const UniaxialCompressionResult fast = run_uniaxial_compression(p, setup.options);
  setup.options.strain_rate = 0.5 * rate;
  const UniaxialCompressionResult slow = run_uniaxial_compression(p, setup.options);
  ASSERT_GT(fast.broken_bonds, 0u);
  ASSERT_TRUE(fast.modulus.found && slow.modulus.found);
  EXPECT_NEAR(fast.youngs_modulus, slow.youngs_modulus, 2e-3 * slow.youngs_modulus);
  EXPECT_NEAR(fast.strength, slow.strength, 0.05 * slow.strength);
}

// The adaptive rate (elastic_speedup, issue #14): the plate moves fast until the first bond
// breaks, then the run goes back to the point before that break and on at the automatic rate.
// On the bulk sample: no bond breaks at the fast rate (every break's strain lies past the
// switch), the curve keeps its strain spacing across the switch, fewer steps are run, and E and
// the strength are those of the constant-rate run within the tolerances of the halving test.
TEST(UniaxialCompression, ElasticSpeedupBreaksNoBondFastAndKeepsModulusAndStrength) {
  const Packing p = test::random_bonded_sample(400, 3, r);
  UniaxialCompressionSetup setup = bulk_sample_setup(p);
  const UniaxialCompressionResult constant = run_uniaxial_compression(p, setup.options);
  setup.options.elastic_speedup = 4.0;
  const UniaxialCompressionResult adaptive = run_uniaxial_compression(p, setup.options);
  ASSERT_GT(constant.broken_bonds, 0u);
  ASSERT_GT(adaptive.broken_bonds, 0u);
  ASSERT_TRUE(std::isfinite(adaptive.rate_switch_strain));
  EXPECT_GT(adaptive.rolled_back_steps, 0);
  EXPECT_NEAR(adaptive.effective_speedup, 4.0, 0.1);
  for (double strain : adaptive.break_strain) EXPECT_GE(strain, adaptive.rate_switch_strain);
  // The plate speeds up smoothly (the points' strain spacing grows), then the points are equally
  // spaced in strain. The plate slows down right after one of them (a point is the state at the
  // start of its measured step, which still runs fast): the gap after it is one fast step longer
  // (a few % of the spacing). The last point may end a shorter step, at max_strain.
  const std::vector<UniaxialCompressionPoint>& c = adaptive.curve;
  const double spacing = c[c.size() / 2].strain - c[c.size() / 2 - 1].strain;
  bool ramped = false, switch_is_a_point = false;
  for (std::size_t k = 1; k + 1 < c.size(); ++k) {
    const double gap = c[k].strain - c[k - 1].strain;
    const bool after_switch =
        c[k - 1].strain < adaptive.rate_switch_strain && adaptive.rate_switch_strain < c[k - 1].strain + 0.1 * spacing;
    switch_is_a_point |= after_switch;
    if (after_switch) {
      EXPECT_GT(gap, spacing) << k;
      EXPECT_LT(gap, 1.1 * spacing) << k;
    } else if (ramped) {
      EXPECT_NEAR(gap, spacing, 1e-9 * spacing) << k;
    } else {
      EXPECT_LT(gap, spacing * (1 + 1e-9)) << k;
      if (k > 1) {
        EXPECT_GT(gap, c[k - 1].strain - c[k - 2].strain) << k;
      }
      ramped = gap > spacing * (1 - 1e-9);
    }
  }
  EXPECT_TRUE(ramped);
  EXPECT_TRUE(switch_is_a_point);
  // The sample slows down with the plate: from the first point after the switch on, its kinetic
  // energy is that of the constant-rate run's point nearest in strain (1.00-1.03 times it here), not
  // elastic_speedup^2 times it, nor swinging between 0.55 and 1.33 times it as when the sample
  // keeps the fast run's velocities (measured).
  std::size_t first_slow = 0;
  while (first_slow < c.size() && c[first_slow].strain <= adaptive.rate_switch_strain) ++first_slow;
  ASSERT_LT(first_slow + 6, c.size());
  for (std::size_t k = first_slow; k < first_slow + 6; ++k) {
    std::size_t same = 0;  // the constant-rate point nearest in strain
    while (same + 1 < constant.curve.size() && std::abs(constant.curve[same + 1].strain - c[k].strain) <
                                                   std::abs(constant.curve[same].strain - c[k].strain))
      ++same;
    EXPECT_NEAR(c[k].kinetic_energy, constant.curve[same].kinetic_energy, 0.1 * constant.curve[same].kinetic_energy)
        << k;
  }
  EXPECT_LT(adaptive.steps + adaptive.rolled_back_steps, constant.steps);
  ASSERT_TRUE(constant.modulus.found && adaptive.modulus.found);
  EXPECT_NEAR(adaptive.youngs_modulus, constant.youngs_modulus, 2e-3 * constant.youngs_modulus);
  EXPECT_NEAR(adaptive.strength, constant.strength, 0.05 * constant.strength);
}

// A snapshot requested at an applied stress is taken at the first curve point at or above it,
// once; one never reached gives none.
TEST(UniaxialCompression, StressSnapshotsAreTakenAtTheFirstPointThatReachesThem) {
  UniaxialCompressionOptions o = options();
  o.max_strain = 0.003;
  o.strain_rate = 1e6;
  o.samples = 50;
  const double top = 0.003 * sc_modulus();
  o.snapshot_stresses = {0.5 * top, 2.0 * top};
  o.snapshot_strains = {0.001};
  const UniaxialCompressionResult res = run_uniaxial_compression(sc_column(8), o);
  ASSERT_EQ(res.snapshots.size(), 2u);
  EXPECT_EQ(res.snapshots[0].requested_strain, 0.001);
  const UniaxialCompressionSnapshot& s = res.snapshots[1];
  EXPECT_EQ(s.requested_stress, 0.5 * top);
  EXPECT_TRUE(std::isnan(s.requested_strain));
  std::size_t k = 0;
  while (res.curve[k].stress < 0.5 * top) ++k;
  EXPECT_EQ(s.strain, res.curve[k].strain);
  EXPECT_EQ(s.stress, res.curve[k].stress);
  EXPECT_NEAR(s.stress, 0.5 * top, 0.05 * top);  // 50 points over the run: within one point's step
  EXPECT_EQ(s.particle_stress.size(), res.particles);
}

TEST(UniaxialCompression, BadOptionsAreInputErrors) {
  const Packing column = sc_column(4);
  UniaxialCompressionOptions o = options();
  o.sides = "closed";
  EXPECT_THROW(run_uniaxial_compression(column, o), InputError);
  o = options();
  o.strain_rate = -1;
  EXPECT_THROW(run_uniaxial_compression(column, o), InputError);
  o = options();
  o.elastic_speedup = 0.5;
  EXPECT_THROW(run_uniaxial_compression(column, o), InputError);
  o = options();
  o.elastic_speedup = 4.0;
  o.solver = "static";
  EXPECT_THROW(run_uniaxial_compression(column, o), InputError);
  o = options();
  o.snapshot_stresses = {-1e6};
  EXPECT_THROW(run_uniaxial_compression(column, o), InputError);
  Packing unbonded = column;
  unbonded.bonds = Bonds{};
  EXPECT_THROW(run_uniaxial_compression(unbonded, options()), InputError);
}
