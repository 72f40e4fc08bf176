// Per-particle-type parameters of the linear contact model with local damping
// (vem-void-expansion-method §2.1, doh-elastic-properties §2.1).
#pragma once

#include <string>
#include <vector>

namespace packlab::dem {

struct TypeParams {
  double normal_stiffness = 1.0e2;  // k_n [N/m]
  double shear_stiffness = 1.0e1;   // k_s [N/m]
  double friction = 0.0;            // Coulomb coefficient mu [-]
  double density = 1.0e3;           // [kg/m^3] (used when the packing has none per particle)
  double damping = 0.7;             // local damping coefficient alpha [-], 0 <= alpha < 1
  // Hertz-Mindlin contacts (bpm-inverse-opals eq. 5-10) only:
  double youngs_modulus = 0.0;      // E [Pa]
  double poisson_ratio = 0.25;      // nu [-]
  double restitution = 1.0;         // e [-], 0 < e <= 1
  double rolling_friction = 0.0;    // mu_r [-]
};

// How the stiffnesses of two particles make the stiffness of their contact.
//   particle: PFC's particle stiffnesses in series, k = k_a k_b / (k_a + k_b) (the papers'
//             "particle stiffness": two equal particles give a contact of k/2);
//   contact:  the value is the stiffness of a contact between two particles of that type,
//             mixed types take the harmonic mean 2 k_a k_b / (k_a + k_b) (LAMMPS-style kn).
enum class StiffnessRule { particle, contact };

StiffnessRule stiffness_rule_from_name(const std::string& name);
std::string stiffness_rule_name(StiffnessRule rule);

// Contact stiffness from two per-type values under `rule` (0 if either is 0).
inline double combine_stiffness(double ka, double kb, StiffnessRule rule) {
  if (ka <= 0.0 || kb <= 0.0) return 0.0;
  const double series = ka * kb / (ka + kb);
  return rule == StiffnessRule::particle ? series : 2.0 * series;
}

// Validates ranges (InputError naming the type and key).
void validate(const std::vector<TypeParams>& types);

}  // namespace packlab::dem
