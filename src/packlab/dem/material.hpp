// The material of one particle type: what every contact law may read about the particles it
// acts between (vem-void-expansion-method §2.1, doh-elastic-properties §2.1,
// bpm-inverse-opals eq. 5-10). Each property is declared once in material_parameters()
// (name, unit, range, doc; the default is the initializer below); a contact law lists the
// properties it reads (dem/contact/), and only those are validated for it.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "packlab/core/parameter.hpp"

namespace packlab::dem {

struct Material {
  double normal_stiffness = 1.0e2;  // k_n [N/m]
  double shear_stiffness = 1.0e1;   // k_s [N/m]
  double friction = 0.0;            // Coulomb coefficient mu [-]
  double density = 1.0e3;           // [kg/m^3] (used when the packing has none per particle)
  double damping = 0.7;             // local damping coefficient alpha [-], 0 <= alpha < 1
  double youngs_modulus = 0.0;      // E [Pa]
  double poisson_ratio = 0.25;      // nu [-]
  double restitution = 1.0;         // e [-], 0 < e <= 1
  double rolling_friction = 0.0;    // mu_r [-]
  double work_of_adhesion = 0.0;    // W = 2 gamma [J/m^2]
  double adhesion_range = 0.0;      // separation at which the attraction ends [m]
  // DLVO law (dem/contact/dlvo.hpp); defaults: alumina in water at 25 C (docs/bd.md).
  double hamaker_constant = 3.67e-20;   // A [J]
  double surface_potential = 0.0;       // psi_0 [V]
  double debye_length = 10.0e-9;        // 1/kappa [m]
  double relative_permittivity = 78.5;  // eps_r [-]
  double dlvo_min_separation = 0.4e-9;  // h_min [m]
  double dlvo_cutoff = 0.25e-6;         // h_cutoff [m]
};

// Every property of Material, declared once. density and damping are read by the engine for
// every law; the others by the laws that list them.
std::span<const Parameter<Material>> material_parameters();
const Parameter<Material>& material_parameter(std::string_view name);

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

// Validates density and damping of every type, and the properties `law_properties` names
// (InputError naming the type and key).
void validate(const std::vector<Material>& types, std::span<const std::string_view> law_properties = {});

}  // namespace packlab::dem
