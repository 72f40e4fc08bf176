// The DLVO pair law (dem/contact/dlvo.hpp) against what is known exactly: its force is -dU/dh
// everywhere (unequal spheres and potentials, h_min, contact spring), its two terms reduce to the
// textbook equal-sphere forms (and the van der Waals term to Derjaguin's -A a / (12 h) near
// contact), the barrier and secondary minimum of generate::dlvo_profile sit where an independent
// dense scan of the textbook expression puts them, and the registry around it (the engine
// accepts it by name, validates the properties it reads, and its force reaches across a gap).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "../input_error.hpp"
#include "packlab/dem/contact/dlvo.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/generate/brownian_dynamics.hpp"

using namespace packlab;
using namespace packlab::dem;

namespace {

constexpr double a = 0.25e-6, kT = 1.380649e-23 * 298.15, eps0 = 8.8541878128e-12;

Dlvo::Params params(double psi_i, double psi_j) { return {1e-3, 3.67e-20, psi_i, psi_j, 10e-9, 78.5, 0.4e-9, 0.25e-6}; }

// The equal-sphere textbook forms, written out independently of the law's general ones.
double textbook_vdw(double A, double h) {
  const double r = 2 * a + h;
  return -A / 6.0 * (2 * a * a / (r * r - 4 * a * a) + 2 * a * a / (r * r) + std::log((r * r - 4 * a * a) / (r * r)));
}
double textbook_hhf(double psi, double h) {
  return 2 * std::numbers::pi * 78.5 * eps0 * a * psi * psi * std::log(1 + std::exp(-h / 10e-9));
}

}  // namespace

TEST(Dlvo, ForceIsMinusTheDerivativeOfTheEnergy) {
  for (const auto& [a1, a2, psi1, psi2] :
       {std::array<double, 4>{a, a, 15e-3, 15e-3}, std::array<double, 4>{a, 0.6 * a, 20e-3, -5e-3},
        std::array<double, 4>{0.3 * a, a, 0.0, 12e-3}}) {
    const Dlvo::Params p = params(psi1, psi2);
    for (const double h : {-2e-9, -0.1e-9, 0.1e-9, 0.7e-9, 2e-9, 8e-9, 13e-9, 40e-9, 120e-9, 240e-9}) {
      const double dh = 1e-6 * std::max(std::abs(h), 1e-9);
      const double numeric =
          -(Dlvo::interaction(p, a1, a2, h + dh).energy - Dlvo::interaction(p, a1, a2, h - dh).energy) / (2 * dh);
      const double analytic = Dlvo::interaction(p, a1, a2, h).force;
      EXPECT_NEAR(analytic, numeric, 1e-6 * std::abs(analytic) + 1e-18) << "h = " << h << " a1 = " << a1;
      // The force-only path gives the same force.
      EXPECT_NEAR(Dlvo::interaction_force(p, a1, a2, h), analytic, 1e-12 * std::abs(analytic) + 1e-30);
    }
    // Zero beyond the cut-off, and the energy continuous there (shifted by U(cut-off)).
    EXPECT_EQ(Dlvo::interaction(p, a1, a2, 0.26e-6).force, 0.0);
    EXPECT_NEAR(Dlvo::interaction(p, a1, a2, 0.25e-6 - 1e-15).energy, 0.0, 1e-6 * kT);
  }
}

TEST(Dlvo, EqualSpheresGiveTheTextbookForms) {
  const Dlvo::Params p = params(15e-3, 15e-3);
  for (const double h : {0.5e-9, 3e-9, 10e-9, 50e-9, 200e-9}) {
    const double vdw = Dlvo::van_der_waals(p, a, a, h).energy;
    const double dl = Dlvo::double_layer(p, a, a, h).energy;
    EXPECT_NEAR(vdw, textbook_vdw(p.hamaker_constant, h), 1e-9 * std::abs(vdw)) << h;
    // (The textbook form's log(1 + x) keeps ~1e-7 of x = 2e-9 at 200 nm; the law uses log1p.)
    EXPECT_NEAR(dl, textbook_hhf(15e-3, h), 1e-6 * std::abs(dl)) << h;
  }
  // Derjaguin's limit near contact: U_A -> -A a / (12 h) (1 + O((h/a) ln(a/h))).
  for (const double h : {0.05e-9, 0.5e-9}) {
    const double ratio = Dlvo::van_der_waals(p, a, a, h).energy / (-p.hamaker_constant * a / (12 * h));
    EXPECT_NEAR(ratio, 1.0, 3.0 * h / a * std::log(a / h)) << h;
  }
  // Opposite potentials of equal size attract (the (psi_1 - psi_2)^2 ln(1 - e^-kh) term).
  EXPECT_LT(Dlvo::double_layer(params(15e-3, -15e-3), a, a, 5e-9).energy, 0.0);
}

TEST(Dlvo, BarrierAndSecondaryMinimumAgreeWithADenseScanOfTheAnalyticPotential) {
  // The defaults of generate bd (alumina in water, 1/kappa = 10 nm): no barrier at 11 mV, one
  // from 12 mV on (doh-elastic-properties §2.2: "a secondary minimum appears for psi_0 >= 12 mV"),
  // and at 15 mV a barrier 5.62 kT above the secondary minimum (the paper: 5.65 kT).
  EXPECT_FALSE(generate::dlvo_profile(params(11e-3, 11e-3), a, kT).has_barrier);
  for (const double psi : {12e-3, 13e-3, 14e-3, 15e-3}) {
    const generate::DlvoProfile prof = generate::dlvo_profile(params(psi, psi), a, kT);
    ASSERT_TRUE(prof.has_barrier) << psi;
    // Independent: 2e5 log-spaced points of the textbook forms.
    const auto u = [&](double h) { return (textbook_vdw(3.67e-20, h) + textbook_hhf(psi, h)) / kT; };
    const int n = 200000;
    double best_max = -1e300, h_max = 0;
    int k_max = -1;
    std::vector<double> hs(n), us(n);
    for (int k = 0; k < n; ++k) {
      hs[k] = 0.4e-9 * std::pow(0.25e-6 / 0.4e-9, static_cast<double>(k) / (n - 1));
      us[k] = u(hs[k]);
    }
    for (int k = 1; k + 1 < n; ++k)
      if (us[k] >= us[k - 1] && us[k] > us[k + 1]) {
        k_max = k;
        best_max = us[k];
        h_max = hs[k];
        break;
      }
    ASSERT_GE(k_max, 0);
    const auto it = std::min_element(us.begin() + k_max, us.end());
    const double best_min = *it, h_min = hs[static_cast<std::size_t>(it - us.begin())];
    EXPECT_NEAR(prof.barrier_kT, best_max, 1e-6) << psi;
    EXPECT_NEAR(prof.barrier_separation, h_max, 1e-4 * h_max) << psi;
    EXPECT_NEAR(prof.secondary_kT, best_min, 1e-6) << psi;
    EXPECT_NEAR(prof.secondary_separation, h_min, 1e-3 * h_min) << psi;
    // At the extrema the force vanishes.
    const Dlvo::Params p = params(psi, psi);
    const double scale = kT / 10e-9;
    EXPECT_LT(std::abs(Dlvo::potential(p, a, a, prof.barrier_separation).force), 1e-9 * scale);
    EXPECT_LT(std::abs(Dlvo::potential(p, a, a, prof.secondary_separation).force), 1e-9 * scale);
  }
  const generate::DlvoProfile at15 = generate::dlvo_profile(params(15e-3, 15e-3), a, kT);
  EXPECT_NEAR(at15.barrier_above_secondary_kT, 5.62, 0.01);
  EXPECT_NEAR(at15.barrier_kT, 4.44, 0.01);
}

TEST(Dlvo, EngineRunsTheLawByNameAndValidatesItsProperties) {
  EXPECT_NE(std::find(contact_law_names().begin(), contact_law_names().end(), std::string("dlvo")),
            contact_law_names().end());
  Material m;
  m.normal_stiffness = 1e-3;
  m.density = 3690;
  m.damping = 0.0;
  m.surface_potential = 0.0;
  EngineConfig c;
  c.contact_law = "dlvo";
  c.types = {m};
  c.threads = 1;
  c.time_step = 1e-12;
  Packing p;
  p.box.lo = {-5 * a, -5 * a, -5 * a};
  p.box.length = {10 * a, 10 * a, 10 * a};
  p.box.periodic = {false, false, false};
  const double gap = 20e-9;  // van der Waals only: the spheres attract across the gap
  p.add({-a - 0.5 * gap, 0, 0}, a);
  p.add({a + 0.5 * gap, 0, 0}, a);
  Engine engine(p, c);
  engine.run(1);
  const auto v = engine.packing().velocity;
  EXPECT_GT(v[0].x, 0.0);
  EXPECT_LT(v[1].x, 0.0);
  // One step from rest: |v| is F dt / m (or half of it, as a synchronous velocity) with the law's force.
  const double mass = 3690 * 4.0 / 3.0 * std::numbers::pi * a * a * a;
  const Dlvo::Params law = Dlvo::mix(m, m, c.stiffness_rule);
  const double ratio = v[1].x / (Dlvo::interaction_force(law, a, a, gap) * 1e-12 / mass);
  EXPECT_TRUE(std::abs(ratio - 1.0) < 1e-6 || std::abs(ratio - 0.5) < 1e-6) << ratio;
  c.types[0].debye_length = 0.0;
  EXPECT_NE(test::error_of([&] { Engine bad(p, c); }).find("debye_length"), std::string::npos);
}
