#include "packlab/dem/relax.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"

namespace packlab::dem {

std::string RelaxResult::reason() const {
  return stop == RelaxStop::converged
             ? fmt::format("converged: unbalanced force ratio {:.3g} below the tolerance after {} steps",
                           last.unbalanced_force_ratio, steps)
             : fmt::format("step limit: {} steps run, unbalanced force ratio {:.3g}", steps,
                           last.unbalanced_force_ratio);
}

RelaxResult relax(Engine& engine, const RelaxOptions& options) {
  require(options.max_steps >= 0, "steps", static_cast<double>(options.max_steps), ">= 0");
  require(options.tolerance >= 0.0, "tolerance", options.tolerance, ">= 0 (0 = run all steps)");
  require(options.check_interval > 0, "check_interval", static_cast<double>(options.check_interval), "> 0");
  RelaxResult result;
  long done = 0;
  // The loop's state besides the engine: steps done, the history, whether it converged.
  const auto save = [&](std::ostream& out) {
    engine.save_state(out);
    binary::write(out, done);
    binary::write(out, static_cast<int>(result.stop));
    binary::write_vector(out, result.history);
  };
  if (options.resume) {
    engine.load_state(*options.resume);
    int stop = 0;
    binary::read(*options.resume, done, "relaxation steps");
    binary::read(*options.resume, stop, "relaxation stop");
    binary::read_vector(*options.resume, result.history, "relaxation history");
    if (done < 0 || done > options.max_steps || (stop != 0 && stop != 1))
      fail_input("checkpoint is damaged: relaxation state");
    result.stop = static_cast<RelaxStop>(stop);
    if (!result.history.empty()) result.last = result.history.back();
  }
  while (result.stop != RelaxStop::converged && done < options.max_steps) {
    // Measure on the first step of each interval, run the rest unmeasured.
    const Diagnostics d = engine.step_measured();
    ++done;
    result.last = d;
    result.history.push_back(d);
    if (options.on_check) options.on_check(d);
    if (options.tolerance > 0.0 && d.unbalanced_force_ratio < options.tolerance) {
      result.stop = RelaxStop::converged;
      break;
    }
    const long chunk = std::min(options.check_interval - 1, options.max_steps - done);
    engine.run(chunk);
    done += chunk;
    if (options.checkpoint) options.checkpoint(save, false);
  }
  if (options.checkpoint) options.checkpoint(save, true);
  result.steps = done;
  return result;
}

std::string ZeroVelocityRelaxResult::reason() const {
  return converged ? fmt::format(
                         "converged: mean unbalanced force stopped decreasing at {:.4g} N (from {:.4g} N) "
                         "after {} steps",
                         final_unbalanced_force, initial_unbalanced_force, steps)
                   : fmt::format("step limit: {} steps run, mean unbalanced force {:.4g} N (from {:.4g} N)", steps,
                                 final_unbalanced_force, initial_unbalanced_force);
}

double mean_unbalanced_force(const Engine& engine) {
  const auto& P = engine.particles();
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t k = 0; k < P.size(); ++k) {
    if (P.fixed[k]) continue;
    sum += norm(P.force[k]);
    ++count;
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

namespace {
void zero_free_velocities(Engine& engine) {
  auto& P = engine.particles();
  for (std::size_t k = 0; k < P.size(); ++k) {
    if (P.fixed[k]) continue;
    P.velocity[k] = Vec3{};
    P.angular_velocity[k] = Vec3{};
  }
}
}  // namespace

ZeroVelocityRelaxResult relax_zeroing_velocities(Engine& engine, const ZeroVelocityRelaxOptions& options) {
  require(options.max_steps >= 0, "steps", static_cast<double>(options.max_steps), ">= 0");
  require(options.check_interval > 0, "check_interval", static_cast<double>(options.check_interval), "> 0");
  require(options.min_decrease >= 0.0 && options.min_decrease < 1.0, "min_decrease", options.min_decrease, "in [0, 1)");
  require(options.patience > 0, "patience", options.patience, "> 0");
  ZeroVelocityRelaxResult result;
  zero_free_velocities(engine);
  long done = 0;
  double best = std::numeric_limits<double>::infinity();
  int stalled = 0;
  while (done < options.max_steps) {
    const Diagnostics d = engine.step_measured();
    zero_free_velocities(engine);
    ++done;
    const double f = mean_unbalanced_force(engine);
    result.last = d;
    result.history.push_back(d);
    result.unbalanced_force.push_back(f);
    if (result.unbalanced_force.size() == 1) result.initial_unbalanced_force = f;
    result.final_unbalanced_force = f;
    if (options.on_check) options.on_check(d, f);
    if (f < (1.0 - options.min_decrease) * best || !std::isfinite(best)) {
      best = f;
      stalled = 0;
    } else if (++stalled >= options.patience) {
      result.converged = true;
      break;
    }
    if (!(f > 0.0)) {  // nothing left to relax
      result.converged = true;
      break;
    }
    const long chunk = std::min(options.check_interval - 1, options.max_steps - done);
    for (long s = 0; s < chunk; ++s) {
      engine.run(1);
      zero_free_velocities(engine);
    }
    done += chunk;
  }
  result.steps = done;
  return result;
}

}  // namespace packlab::dem
