#include "packlab/dem/material.hpp"

#include <fmt/format.h>

#include <array>

#include "packlab/core/error.hpp"

namespace packlab::dem {

namespace {
using P = Parameter<Material>;
constexpr Range damping_range{0.0, 1.0, false, true};
constexpr Range poisson_range{-1.0, 0.5, true, true};
constexpr Range restitution_range{0.0, 1.0, true, false};
const std::array<P, 17> parameters{{
    {"normal_stiffness", "N/m", "Particle normal stiffness k_n", &Material::normal_stiffness, ranges::positive},
    {"shear_stiffness", "N/m", "Particle shear stiffness k_s", &Material::shear_stiffness, ranges::non_negative},
    {"friction", "", "Coulomb friction coefficient mu", &Material::friction, ranges::non_negative},
    {"density", "kg/m^3", "Density (where the packing has none per particle)", &Material::density, ranges::positive},
    {"damping", "", "Local damping coefficient alpha", &Material::damping, damping_range},
    {"youngs_modulus", "Pa", "Young's modulus E", &Material::youngs_modulus, ranges::positive},
    {"poisson_ratio", "", "Poisson's ratio nu", &Material::poisson_ratio, poisson_range},
    {"restitution", "", "Coefficient of restitution e", &Material::restitution, restitution_range},
    {"rolling_friction", "", "Rolling friction coefficient mu_r", &Material::rolling_friction, ranges::non_negative},
    {"work_of_adhesion", "J/m^2", "Work of adhesion W = 2 gamma (DMT pull-off force 2 pi W R*)",
     &Material::work_of_adhesion, ranges::non_negative},
    {"adhesion_range", "m", "Separation beyond contact over which the adhesive force fades to zero",
     &Material::adhesion_range, ranges::positive},
    {"hamaker_constant", "J", "Hamaker constant A of the particles across the liquid (DLVO van der Waals term)",
     &Material::hamaker_constant, ranges::non_negative},
    {"surface_potential",
     "V",
     "Surface potential psi_0 (DLVO double-layer term, constant potential)",
     &Material::surface_potential,
     {-1.0, 1.0, false, false}},
    {"debye_length", "m", "Debye screening length 1/kappa of the electrolyte", &Material::debye_length,
     ranges::positive},
    {"relative_permittivity", "", "Relative permittivity eps_r of the liquid", &Material::relative_permittivity,
     ranges::positive},
    {"dlvo_min_separation", "m", "Surface separation below which the DLVO force is held constant",
     &Material::dlvo_min_separation, ranges::positive},
    {"dlvo_cutoff", "m", "Surface separation beyond which the DLVO law is zero", &Material::dlvo_cutoff,
     ranges::positive},
}};
}  // namespace

std::span<const Parameter<Material>> material_parameters() { return parameters; }

const Parameter<Material>& material_parameter(std::string_view name) {
  for (const P& p : parameters)
    if (p.name == name) return p;
  throw std::logic_error(fmt::format("material_parameter: no property '{}'", name));
}

StiffnessRule stiffness_rule_from_name(const std::string& name) {
  if (name == "particle") return StiffnessRule::particle;
  if (name == "contact") return StiffnessRule::contact;
  fail_input(fmt::format("stiffness_rule = {}: must be 'particle' (PFC, in series) or 'contact'", name));
}

std::string stiffness_rule_name(StiffnessRule rule) { return rule == StiffnessRule::particle ? "particle" : "contact"; }

void validate(const std::vector<Material>& types, std::span<const std::string_view> law_properties) {
  if (types.empty()) fail_input("no particle type parameters given");
  for (std::size_t t = 0; t < types.size(); ++t) {
    const std::string prefix = fmt::format("type {} ", t);
    for (std::string_view name : {std::string_view("density"), std::string_view("damping")}) {
      const P& p = material_parameter(name);
      require_in_range(prefix, p.name, p.get(types[t]), p.range, p.unit);
    }
    for (std::string_view name : law_properties) {
      const P& p = material_parameter(name);
      require_in_range(prefix, p.name, p.get(types[t]), p.range, p.unit);
    }
  }
}

}  // namespace packlab::dem
