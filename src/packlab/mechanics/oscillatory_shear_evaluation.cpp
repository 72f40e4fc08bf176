// Oscillatory shear: the per-cycle moduli (|G*|, phase angle, G', G'') and the samples and
// cycles as columns.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "packlab/mechanics/oscillatory_shear.hpp"
#include "packlab/mechanics/row_columns.hpp"

namespace packlab::mechanics {

ShearStress shear_stress(const dem::ContactForces& f, const ShearSetup& setup, int regions) {
  ShearStress out;
  out.region_stress.assign(static_cast<std::size_t>(regions), 0.0);
  double plate_force = 0.0;
  for (std::size_t c = 0; c < f.size(); ++c) {
    if (f.j[c] < 0) continue;
    const auto i = static_cast<std::size_t>(f.i[c]), j = static_cast<std::size_t>(f.j[c]);
    const Vec3& l = f.branch[c];
    const Vec3& F = f.force[c];
    // Symmetric x'z' part of 1/2 l (x) F for each end (i: l, -F; j: -l, F: the same product).
    const double lf = 0.5 * 0.5 * (l.x * F.z + l.z * F.x);
    if (setup.region[i] >= 0) out.region_stress[static_cast<std::size_t>(setup.region[i])] += lf;
    if (setup.region[j] >= 0) out.region_stress[static_cast<std::size_t>(setup.region[j])] += lf;
    const bool iu = setup.role[i] == 2, ju = setup.role[j] == 2;
    if (ju && !iu) plate_force += F.x;
    if (iu && !ju) plate_force -= F.x;
    if (f.kind[c] == dem::ContactForces::bond) {
      const double len = norm(l);
      if (len > 0.0) {
        const Vec3 nrm = l * (1.0 / len);
        const double fn = dot(F, nrm);  // > 0: pushes j away (compression)
        const double fs = norm(F - fn * nrm);
        out.max_bond_tension = std::max(out.max_bond_tension, -fn);
        out.max_bond_shear_force = std::max(out.max_bond_shear_force, fs);
      }
    }
  }
  // particle_stress sums l_a F_b with l from the particle to its partner and F the force on
  // the particle: for i that is l (x) (-F); tension positive. The sum above used l (x) F.
  const double region_volume = setup.area * setup.region_thickness;
  for (double& s : out.region_stress) {
    s = -s / region_volume;
    out.stress += s;
  }
  out.stress /= static_cast<double>(regions);
  out.plate_stress = -plate_force / setup.area;
  return out;
}

ShearCycle evaluate_cycle(const std::vector<ShearSample>& samples, int cycle) {
  ShearCycle c;
  c.cycle = cycle;
  // Least squares sigma = a sin(phi) + b cos(phi) + c0 (normal equations of three unknowns).
  double smin = std::numeric_limits<double>::infinity(), smax = -smin, gmin = smin, gmax = -smin;
  double pmin = smin, pmax = -smin;
  double Sss = 0, Scc = 0, Ssc = 0, Ss = 0, Sc = 0, S1 = 0, Sys = 0, Syc = 0, Sy = 0;
  double Gs = 0, Gc = 0, G1 = 0;
  for (const auto& x : samples) {
    if (x.cycle != cycle) continue;
    smin = std::min(smin, x.stress);
    smax = std::max(smax, x.stress);
    pmin = std::min(pmin, x.plate_stress);
    pmax = std::max(pmax, x.plate_stress);
    gmin = std::min(gmin, x.strain);
    gmax = std::max(gmax, x.strain);
    const double s = std::sin(x.phase), co = std::cos(x.phase);
    Sss += s * s;
    Scc += co * co;
    Ssc += s * co;
    Ss += s;
    Sc += co;
    S1 += 1.0;
    Sys += x.stress * s;
    Syc += x.stress * co;
    Sy += x.stress;
    Gs += x.strain * s;
    Gc += x.strain * co;
    G1 += x.strain;
  }
  if (S1 < 3.0 || !(gmax > gmin)) return c;
  // Solve the 3x3 system by Cramer's rule.
  const double M[3][3] = {{Sss, Ssc, Ss}, {Ssc, Scc, Sc}, {Ss, Sc, S1}};
  auto det3 = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  auto solve = [&](double r0, double r1, double r2, double out[3]) {
    const double d = det3(M);
    for (int col = 0; col < 3; ++col) {
      double A[3][3];
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) A[r][k] = M[r][k];
      A[0][col] = r0;
      A[1][col] = r1;
      A[2][col] = r2;
      out[col] = det3(A) / d;
    }
  };
  double stress_fit[3], strain_fit[3];
  solve(Sys, Syc, Sy, stress_fit);
  solve(Gs, Gc, G1, strain_fit);
  // Phase of the stress relative to the strain's own phase (the strain is a sine by
  // construction; fitting it too removes any sampling offset).
  const double stress_phase = std::atan2(stress_fit[1], stress_fit[0]);
  const double strain_phase = std::atan2(strain_fit[1], strain_fit[0]);
  double delta = stress_phase - strain_phase;
  while (delta > std::numbers::pi) delta -= 2.0 * std::numbers::pi;
  while (delta < -std::numbers::pi) delta += 2.0 * std::numbers::pi;
  c.strain_amplitude = 0.5 * (gmax - gmin);
  c.stress_amplitude = 0.5 * (smax - smin);
  c.complex_modulus = c.stress_amplitude / c.strain_amplitude;
  c.phase_angle = delta;
  c.storage_modulus = c.complex_modulus * std::cos(delta);
  c.loss_modulus = c.complex_modulus * std::sin(delta);
  c.plate_storage_modulus = 0.5 * (pmax - pmin) / c.strain_amplitude * std::cos(delta);
  return c;
}

Columns shear_sample_columns(const std::vector<ShearSample>& samples, int regions) {
  using S = ShearSample;
  Columns t;
  add_row_column(
      t, "cycle", samples, [](const S& s) { return s.cycle; }, Column::Kind::integer);
  add_row_column(
      t, "step", samples, [](const S& s) { return s.step; }, Column::Kind::integer);
  add_real_row_columns(t, samples,
                       {{"time", &S::time},
                        {"phase", &S::phase},
                        {"strain", &S::strain},
                        {"stress", &S::stress},
                        {"plate_stress", &S::plate_stress}},
                       10);
  std::vector<std::vector<double>> region(static_cast<std::size_t>(std::max(regions, 0)));
  for (const auto& s : samples)
    for (std::size_t k = 0; k < region.size() && k < s.region_stress.size(); ++k)
      region[k].push_back(s.region_stress[k]);
  for (std::size_t k = 0; k < region.size(); ++k)
    t.add("region_" + std::to_string(k), std::move(region[k]), Column::Kind::real, 10);
  add_real_row_columns(t, samples, {{"kinetic_energy", &S::kinetic_energy}, {"strain_energy", &S::strain_energy}}, 6);
  return t;
}

Columns shear_cycle_columns(const std::vector<ShearCycle>& cycles) {
  using C = ShearCycle;
  Columns t;
  add_row_column(
      t, "cycle", cycles, [](const C& c) { return c.cycle; }, Column::Kind::integer);
  add_real_row_columns(t, cycles,
                       {{"strain_amplitude", &C::strain_amplitude},
                        {"stress_amplitude", &C::stress_amplitude},
                        {"complex_modulus", &C::complex_modulus},
                        {"phase_angle", &C::phase_angle},
                        {"storage_modulus", &C::storage_modulus},
                        {"loss_modulus", &C::loss_modulus},
                        {"plate_storage_modulus", &C::plate_storage_modulus}},
                       10);
  return t;
}

}  // namespace packlab::mechanics
