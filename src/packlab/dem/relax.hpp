// Runs the engine until the mean unbalanced force ratio falls below a tolerance or a step
// limit is reached, whichever comes first, and says which.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "packlab/dem/engine.hpp"

namespace packlab::dem {

struct RelaxOptions {
  long max_steps = 100000;
  double tolerance = 1e-3;   // unbalanced force ratio; 0 runs exactly max_steps steps
  long check_interval = 100; // steps between diagnostics
  // Called after each check with the diagnostics (progress reporting, logging).
  std::function<void(const Diagnostics&)> on_check;
};

enum class RelaxStop { converged, step_limit };

struct RelaxResult {
  long steps = 0;
  RelaxStop stop = RelaxStop::step_limit;
  Diagnostics last;                  // diagnostics at the last check
  std::vector<Diagnostics> history;  // one entry per check
  std::string reason() const;
};

RelaxResult relax(Engine& engine, const RelaxOptions& options);

}  // namespace packlab::dem
