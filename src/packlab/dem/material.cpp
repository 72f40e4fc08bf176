#include "packlab/dem/material.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "packlab/core/error.hpp"

namespace packlab::dem {

StiffnessRule stiffness_rule_from_name(const std::string& name) {
  if (name == "particle") return StiffnessRule::particle;
  if (name == "contact") return StiffnessRule::contact;
  fail_input(fmt::format("stiffness_rule = {}: must be 'particle' (PFC, in series) or 'contact'", name));
}

std::string stiffness_rule_name(StiffnessRule rule) {
  return rule == StiffnessRule::particle ? "particle" : "contact";
}

void validate(const std::vector<TypeParams>& types) {
  if (types.empty()) fail_input("no particle type parameters given");
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < types.size(); ++t) {
    const auto& p = types[t];
    const std::string k = fmt::format("type {} ", t);
    require(std::isfinite(p.normal_stiffness) && p.normal_stiffness > 0.0, k + "normal_stiffness",
            p.normal_stiffness, "> 0 N/m");
    require(std::isfinite(p.shear_stiffness) && p.shear_stiffness >= 0.0, k + "shear_stiffness",
            p.shear_stiffness, ">= 0 N/m");
    require(p.friction >= 0.0 && p.friction < inf, k + "friction", p.friction, ">= 0");
    require(std::isfinite(p.density) && p.density > 0.0, k + "density", p.density, "> 0 kg/m^3");
    require(p.damping >= 0.0 && p.damping < 1.0, k + "damping", p.damping, "in [0, 1)");
  }
}

}  // namespace packlab::dem
