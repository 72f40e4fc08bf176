// Two relaxations of a packing held in an engine:
//  - relax(): runs the engine (with its damping) until the mean unbalanced force ratio falls
//    below a tolerance or a step limit is reached, whichever comes first, and says which;
//  - relax_zeroing_velocities(): the procedure of doh-elastic-properties §2.2 for freshly bonded
//    structures: single steps, after each of which every translational and rotational velocity
//    is set to zero (a steepest-descent walk x += F/m dt^2 that removes overlaps and bond
//    strains without moving particles far), until the mean unbalanced force stops decreasing.
#pragma once

#include <functional>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "packlab/dem/engine.hpp"

namespace packlab::dem {

struct RelaxOptions {
  long max_steps = 100000;
  double tolerance = 1e-3;    // unbalanced force ratio; 0 runs exactly max_steps steps
  long check_interval = 100;  // steps between diagnostics
  // Called after each check with the diagnostics (progress reporting, logging).
  std::function<void(const Diagnostics&)> on_check;
  // Resumable runs (`packlab relax --checkpoint DIR`, cli/checkpoint.hpp): `checkpoint` is
  // called between two checks with a writer of the whole state (the engine's and the loop's),
  // and once more at the end (`end` true); a run given `resume`, a stream positioned at such a
  // state, loads it into the engine and goes on exactly as the saved run would have.
  std::function<void(const std::function<void(std::ostream&)>& state, bool end)> checkpoint;
  std::istream* resume = nullptr;
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

// The §2.2 procedure. The paper stops "as soon as the mean unbalanced force has decreased to a
// constant value"; the criterion used here (documented in docs/shear.md): every
// check_interval steps the mean unbalanced force <|F_i|> over the free particles [N] is taken;
// a check counts as progress when it is below (1 - min_decrease) times the lowest value seen so
// far; the run stops after `patience` checks in a row without progress (or at max_steps).
// Fixed particles keep their velocities (prescribed motion is not disturbed).
struct ZeroVelocityRelaxOptions {
  long max_steps = 100000;
  long check_interval = 50;    // steps between two values of the mean unbalanced force
  double min_decrease = 0.01;  // relative decrease that counts as progress
  int patience = 5;            // checks in a row without progress that end the run
  std::function<void(const Diagnostics&, double mean_unbalanced_force)> on_check;
};

struct ZeroVelocityRelaxResult {
  long steps = 0;
  bool converged = false;               // stopped by the criterion, not by max_steps
  double initial_unbalanced_force = 0;  // <|F_i|> at the first check [N]
  double final_unbalanced_force = 0;    // at the last check [N]
  Diagnostics last;
  std::vector<Diagnostics> history;      // one entry per check
  std::vector<double> unbalanced_force;  // <|F_i|> per check [N]
  std::string reason() const;
};

// Mean |F_i| over the free particles of the forces of the last step [N] (0 when none is free).
double mean_unbalanced_force(const Engine& engine);

ZeroVelocityRelaxResult relax_zeroing_velocities(Engine& engine, const ZeroVelocityRelaxOptions& options);

}  // namespace packlab::dem
