// The time-step rules (engine.hpp TimeStepRule): the global estimate from each particle's own
// contact stiffness and its bonds, the heaviest particle's step (the cap of the refreshed
// rules); the refreshed rules themselves are applied in the step loop (step.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "packlab/core/error.hpp"
#include "packlab/dem/engine.hpp"

namespace packlab::dem {

TimeStepRule time_step_rule_from_name(const std::string& name) {
  if (name == "global") return TimeStepRule::global;
  if (name == "contacts") return TimeStepRule::contacts;
  if (name == "stiffness_sum") return TimeStepRule::stiffness_sum;
  fail_input(fmt::format("time_step_rule = {}: must be 'global', 'contacts' or 'stiffness_sum'", name));
}

std::string time_step_rule_name(TimeStepRule rule) {
  switch (rule) {
    case TimeStepRule::global: return "global";
    case TimeStepRule::contacts: return "contacts";
    case TimeStepRule::stiffness_sum: return "stiffness_sum";
  }
  return "global";
}

double Engine::critical_time_step() const {
  double dt = std::numeric_limits<double>::infinity();
  std::visit(
      [&](const auto& model) {
        using Law = std::decay_t<decltype(model.law)>;
        for (std::size_t i = 0; i < particles_.size(); ++i) {
          if (particles_.fixed[i]) continue;
          const int t = particles_.type[i];
          const double k = Law::stiffness(model.pair_params[t * model.type_count + t], particles_.radius[i]);
          if (k > 0.0) dt = std::min(dt, std::sqrt(particles_.mass[i] / k));
        }
      },
      model_);
  std::visit(
      [&](const auto& bonds) {
    const double inf = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < bonds_.i.size(); ++b) {
      if (bonds_.state[b] != 0) continue;
      const auto i = static_cast<std::size_t>(bonds_.i[b]), j = static_cast<std::size_t>(bonds_.j[b]);
      const double m = std::min(particles_.fixed[i] ? inf : particles_.mass[i], particles_.fixed[j] ? inf : particles_.mass[j]);
      const double k = bonds.law.stiffness(bonds.params(bonds_.material[b]), particles_.radius[i],
                                           particles_.radius[j], bonds_.rest_length[b]);
      if (std::isfinite(m)) dt = std::min(dt, std::sqrt(m / k));
    }
      },
      bond_model_);
  return config_.time_step_safety * dt;
}

double Engine::heaviest_particle_time_step() const {
  double dt = 0.0;
  std::visit(
      [&](const auto& model) {
        using Law = std::decay_t<decltype(model.law)>;
        for (std::size_t i = 0; i < particles_.size(); ++i) {
          const int t = particles_.type[i];
          const double k = Law::stiffness(model.pair_params[t * model.type_count + t], particles_.radius[i]);
          if (k > 0.0) dt = std::max(dt, std::sqrt(particles_.mass[i] / k));
        }
      },
      model_);
  return config_.time_step_safety * dt;
}

void Engine::set_time_step(double dt) {
  require(dt > 0.0 && std::isfinite(dt), "time_step", dt, "> 0 s");
  dt_ = dt;
}

}  // namespace packlab::dem
