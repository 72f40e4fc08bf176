#include "packlab/dem/relax.hpp"

#include <fmt/format.h>

#include <algorithm>

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
  while (done < options.max_steps) {
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
  }
  result.steps = done;
  return result;
}

}  // namespace packlab::dem
