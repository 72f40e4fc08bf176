// Oscillatory shear: the per-cycle moduli (|G*|, phase angle, G', G'') and the samples and
// cycles as columns.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "packlab/mechanics/oscillatory_shear.hpp"

namespace packlab::mechanics {

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
  std::vector<double> cycle, step, time, phase, strain, stress, plate, kinetic, strain_energy;
  std::vector<std::vector<double>> region(static_cast<std::size_t>(std::max(regions, 0)));
  for (const auto& s : samples) {
    cycle.push_back(s.cycle);
    step.push_back(static_cast<double>(s.step));
    time.push_back(s.time);
    phase.push_back(s.phase);
    strain.push_back(s.strain);
    stress.push_back(s.stress);
    plate.push_back(s.plate_stress);
    for (std::size_t k = 0; k < region.size() && k < s.region_stress.size(); ++k) region[k].push_back(s.region_stress[k]);
    kinetic.push_back(s.kinetic_energy);
    strain_energy.push_back(s.strain_energy);
  }
  Columns t;
  t.add("cycle", std::move(cycle), Column::Kind::integer);
  t.add("step", std::move(step), Column::Kind::integer);
  t.add("time", std::move(time), Column::Kind::real, 10);
  t.add("phase", std::move(phase), Column::Kind::real, 10);
  t.add("strain", std::move(strain), Column::Kind::real, 10);
  t.add("stress", std::move(stress), Column::Kind::real, 10);
  t.add("plate_stress", std::move(plate), Column::Kind::real, 10);
  for (std::size_t k = 0; k < region.size(); ++k)
    t.add("region_" + std::to_string(k), std::move(region[k]), Column::Kind::real, 10);
  t.add("kinetic_energy", std::move(kinetic), Column::Kind::real, 6);
  t.add("strain_energy", std::move(strain_energy), Column::Kind::real, 6);
  return t;
}

Columns shear_cycle_columns(const std::vector<ShearCycle>& cycles) {
  std::vector<double> cycle, strain_amplitude, stress_amplitude, complex_modulus, phase_angle, storage, loss, plate;
  for (const auto& c : cycles) {
    cycle.push_back(c.cycle);
    strain_amplitude.push_back(c.strain_amplitude);
    stress_amplitude.push_back(c.stress_amplitude);
    complex_modulus.push_back(c.complex_modulus);
    phase_angle.push_back(c.phase_angle);
    storage.push_back(c.storage_modulus);
    loss.push_back(c.loss_modulus);
    plate.push_back(c.plate_storage_modulus);
  }
  Columns t;
  t.add("cycle", std::move(cycle), Column::Kind::integer);
  t.add("strain_amplitude", std::move(strain_amplitude), Column::Kind::real, 10);
  t.add("stress_amplitude", std::move(stress_amplitude), Column::Kind::real, 10);
  t.add("complex_modulus", std::move(complex_modulus), Column::Kind::real, 10);
  t.add("phase_angle", std::move(phase_angle), Column::Kind::real, 10);
  t.add("storage_modulus", std::move(storage), Column::Kind::real, 10);
  t.add("loss_modulus", std::move(loss), Column::Kind::real, 10);
  t.add("plate_storage_modulus", std::move(plate), Column::Kind::real, 10);
  return t;
}

}  // namespace packlab::mechanics
