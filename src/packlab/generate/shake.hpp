// Monte-Carlo shaking of a hard-sphere packing (scrm-bimodal-packs.txt §3.2), for any packing
// and any number of size classes.
//
// A visit to particle i (radius a_i) gathers its testing window (the centres closer than
// (1 + R_sh) a_i + a_j: a near-neighbour list, refreshed at every visit) and makes up to N_sh
// trials, by one of two move rules (`move_rule`):
//
// "metropolis" (the default; §3.2's first paragraph): trial l moves the centre to a point
// uniformly distributed in the shake window |x' - x_i| < R_sh a_i and is accepted if the sphere
// there overlaps no other; otherwise the next trial is drawn, up to N_sh. With N_sh = 1 this is
// the textbook Metropolis move of hard spheres, whose stationary state is the equilibrium
// ensemble at the packing's volume fraction (detailed balance: the trial is symmetric and every
// overlap-free state has the same weight); with N_sh > 1 a sphere in a tight cage is more
// likely to move than with one trial, a bias towards cages with more free volume.
//
// "freest" (§3.2's speed-up, as read here): trial l draws a uniformly random direction u_l and finds its
// collision-limited free distance dt_l, the smallest root over the window of |x_i + u_l t - x_j| = a_i + a_j (eq. 9).
// The move goes along the trial direction with the largest free distance, dt = max_l dt_l (the paper's "Delta t = max_l
// Delta t^l with the corresponding direction u^l"), by an amplitude uniform on [0, min(dt, R_sh a_i)]: every move is
// overlap-free, and it tends to move a sphere away from its contacts towards the middle of its cage, which breaks
// "locked" local arrangements. Trials stop early once a direction is free over the whole window. A sphere blocked in
// every trial direction does not move. This rule has no detailed balance: it empties the first ~0.005 a beyond contact
// and piles pairs up at 2.01-2.03 a (docs/scrm.md, "Which move rule"). A global shake (sweep) visits every particle
// once, in a random order. With `adaptive`, R_sh (per class) grows by `adapt_factor` when dt exceeded it and shrinks
// otherwise, within [min_window, max_window]. Along open box axes centres stay inside the box.
#pragma once

#include <functional>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "packlab/core/packing.hpp"
#include "packlab/core/random.hpp"

namespace packlab::generate {

struct ShakeParams {
  std::string move_rule = "metropolis";  // "metropolis" or "freest" (see above)
  double window = 0.02;                  // R_sh: shake window radius in units of the particle's radius
  int max_trials = 150;                  // N_sh: trials per visit
  bool adaptive = false;                 // adapt R_sh per class
  double adapt_factor = 1.05;
  double min_window = 1e-4;
  double max_window = 0.5;
  void validate() const;
};

struct ShakeStats {
  long sweeps = 0;
  long long visits = 0;
  long long trials = 0;    // trial moves (directions or displacements tried)
  long long moves = 0;     // executed moves (visits that moved)
  double mean_step = 0.0;  // mean executed amplitude / a_i
  double seconds = 0.0;
  std::vector<double> window;  // final R_sh per class (largest class first)
};

// The statistics in a checkpoint (binary, InputError when truncated).
void write_shake_stats(std::ostream& out, const ShakeStats& stats);
ShakeStats read_shake_stats(std::istream& in);

class Shaker {
 public:
  // Works on `packing` in place (kept by reference); throws InputError if spheres overlap by
  // more than a relative 1e-9.
  Shaker(Packing& packing, const ShakeParams& params);
  // One global shake.
  void sweep(Random& rng);
  // m global shakes; on_sweep after each.
  void sweeps(long m, Random& rng, const std::function<void(const ShakeStats&)>& on_sweep = {});
  const ShakeStats& stats() const { return stats_; }
  // Between two sweeps: the positions, the statistics and the windows. A shaker of the same
  // packing (radii and box; InputError otherwise) that loads them and gets the same generator
  // state goes on exactly as the saved one would have.
  void save_state(std::ostream& out) const;
  void load_state(std::istream& in);
  // Collision-limited free distance of particle i along unit vector u (eq. 9), up to `limit`.
  double free_distance(int i, const Vec3& u, double limit) const;
  // The same against the neighbours gathered by gather(i, ...) (testing window).
  double free_distance_gathered(int i, const Vec3& u, double limit) const;

 private:
  void visit(int i, Random& rng);
  void visit_metropolis(int i, Random& rng);
  void move_to(int i, const Vec3& x, double step);
  // Whether particle i centred at x would overlap a neighbour gathered by gather(i, ...).
  bool overlaps_gathered(int i, const Vec3& x) const;
  void fill_cells();
  int cell_index(const Vec3& p) const;
  Packing& p_;
  ShakeParams params_;
  bool metropolis_ = true;  // params_.move_rule, decided once (not per visit)
  ShakeStats stats_;
  std::vector<int> klass_;
  std::vector<double> class_radius_;
  double step_sum_ = 0.0;
  // cells
  int n_[3] = {1, 1, 1};
  double h_[3] = {1, 1, 1};
  std::vector<std::vector<int>> cells_;
  std::vector<int> cell_of_, slot_;
  mutable std::vector<std::pair<int, Vec3>> near_;  // testing window: neighbour and its image offset
  void gather(int i, double range) const;
};

}  // namespace packlab::generate
