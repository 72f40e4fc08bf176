// Force-biased algorithm (FBA) for dense random packings of poly- or monodisperse spheres to a
// target porosity (bpm-inverse-opals §2.1, after Mościński, Bargieł, Rycerz & Jacobs 1989 and
// Bezrukov, Bargieł & Stoyan 2002), in a box periodic along any subset of axes; also used to
// place random pores (§4).
//
// Model (every choice is a named parameter below):
//  - Relative radii rho_i (any common scale) are given; the target radii are R_i = s_t rho_i
//    with s_t chosen so that sum 4/3 pi R_i^3 = (1 - target_porosity) V_box.
//  - Start: uniform random centres (along open axes inside [lo + R_i, hi - R_i]).
//  - Two scales, as in the classic FBA: the outer ("nominal") scale s_out, from which the
//    pushing forces come, starts where the spheres would fill the box (volume fraction 1; at
//    most 1.5 s_t, for dilute sets such as pores) and shrinks; the inner ("true") scale s_in = min_pairs d_ij / (rho_i
//    + rho_j) is the largest scale at which the current centres carry no overlap.
//  - Iteration: every pair overlapping at s_out, h_ij = s_out (rho_i + rho_j) - d_ij > 0, pushes
//    i and j apart along their axis by step x h_ij shared in inverse proportion to the sphere
//    volumes (i moves by step h_ij rho_j^3 / (rho_i^3 + rho_j^3)). All displacements of one
//    iteration are computed from the same positions (Jacobi), so the result does not depend on
//    the thread count. One particle moves at most max_move x R_i per iteration. Along open axes
//    a wall keeps each centre in [lo + R_i, hi - R_i] (spheres wholly inside the box).
//  - Then s_out <- max(s_t, s_out - shrink_rate (s_out - s_in)): the nominal diameters shrink
//    towards the true ones, never below the target. With the default rate the nominal diameter
//    reaches the target within ~40 iterations, with the spheres still overlapping: they are
//    jammed there (~2 overlapping pairs per sphere at ~1e-2 overlap), and the overlap removal
//    at the target (step-length fraction of each overlap per iteration, a gradient descent on
//    the overlap energy) creeps: ~15,000 of ~15,700 iterations for 10^4 spheres at porosity
//    0.38 with walls (bench_fba seeds).
//  - Overlap removal with momentum (Polyak's heavy-ball method, Polyak 1964, eq. 9: x_{k+1} =
//    x_k - a grad f(x_k) + b (x_k - x_{k-1})): once s_out is at the target, each sphere's move
//    adds `momentum` times its previous move (what it actually moved: a wall stops it). Along
//    the flat directions of the jammed landscape the moves add up to 1/(1 - b) times the plain
//    step; the packing the run ends in is of the same kind (contacts, g(r)'s first peak and
//    g(2 sqrt3 a) within the scatter of realizations, g(4 a) 0.05 lower: bench_fba seeds,
//    docs/opal-build.md) in 14x fewer iterations at b = 0.9. momentum = 0 is the plain first
//    version, bit for bit. (A slower contraction,
//    shrink_rate 0.001, avoids the jam altogether in ~700 iterations but ends in another kind
//    of packing: 5.45 instead of 6.38 contacts within 1 % per sphere.)
//  - Stop criterion (documented, checked): the maximum relative overlap at the target radii,
//    1 - s_in / s_t = max_pairs (R_i + R_j - d_ij) / (R_i + R_j), is <= tolerance (target
//    reached); or max_iterations (reported, status max_iterations).
//  - The result has radii R_i exactly (porosity exactly the target) and is verified by an
//    independent pair search (generate::min_contact_ratio): its max relative overlap is reported
//    and must be <= tolerance when the target is reached.
#pragma once

#include <array>
#include <functional>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "packlab/core/neighbor_list.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/size_classes.hpp"

namespace packlab::generate {

struct FbaParams {
  double target_porosity = 0.38;  // 1 - sum of sphere volumes / box volume, in [0.30, 1)
  double tolerance = 1e-3;        // accepted max relative overlap at the end, in (0, 0.1]
  double shrink_rate = 0.01;      // fraction of (s_out - s_in) removed per iteration, in (0, 1]
  double step = 1.0;              // fraction of each pair's overlap removed per iteration, (0, 1]
  double momentum = 0.9;          // heavy-ball factor of the overlap removal at the target, [0, 1)
  double max_move = 0.5;          // per-iteration displacement cap in target radii, (0, 2]
  long max_iterations = 100000;   // >= 1
  int threads = 1;
  void validate() const;  // InputError naming key, value and range
};

enum class FbaStop { target_reached, max_iterations };
std::string fba_stop_name(FbaStop stop);

struct FbaStatus {
  long iteration = 0;
  double outer_scale = 0;  // s_out / s_t
  double inner_scale = 0;  // s_in / s_t (1 - max relative overlap at the target radii)
  double max_overlap = 0;  // max_pairs (R_i + R_j - d_ij)/(R_i + R_j) at the target radii
  double porosity = 0;     // target porosity (the radii are the target radii)
  double seconds = 0;
  long overlapping_pairs = 0;  // pairs overlapping at s_out in this iteration
  FbaStop stop = FbaStop::max_iterations;
};

struct FbaResult {
  Packing packing;  // radii R_i, type structural, box as given
  FbaStatus status;
  double verified_max_overlap = 0;  // independent pair search on the result
  std::vector<FbaStatus> history;   // every `history_every` iterations (and the last)
};

// The algorithm as a run that can stop and go on: run() advances by whole iterations, and
// between two of them save_state() writes everything the next iteration depends on (positions,
// the nominal scale, the iteration count, the history and the neighbour list, whose pair order
// sets the order of the sums). A run loaded from that state goes on exactly as the saved one
// would have: the same positions bit for bit, whatever the thread count.
class FbaRun {
 public:
  // Draws the start (uniform random centres) from `rng`; InputError on bad input.
  FbaRun(const Box& box, std::vector<double> relative_radius, const FbaParams& params, Random& rng,
         long history_every = 0);
  // A run saved by save_state() (box, radii, parameters included); InputError if damaged.
  // `threads` > 0 replaces the saved thread count (the result does not depend on it).
  static FbaRun load_state(std::istream& in, int threads = 0);
  void save_state(std::ostream& out) const;

  // At most `iterations` more iterations (all that are needed when negative); true when the
  // run has stopped (target reached or max_iterations). `progress` is called every 50
  // iterations and at the stop.
  bool run(long iterations = -1, const std::function<void(const FbaStatus&)>& progress = {});
  bool finished() const { return finished_; }
  const FbaStatus& status() const { return status_; }
  // The packing at the target radii, verified by an independent pair search (after the stop).
  FbaResult result() const;

 private:
  FbaRun() = default;
  void setup();  // derived sizes and checks, from box_, rho_ and params_
  void iterate(const std::function<void(const FbaStatus&)>& progress);

  Box box_;
  std::vector<double> rho_;  // relative radii
  FbaParams params_;
  long history_every_ = 0;
  // Derived by setup().
  double s_t_ = 0.0, skin_ = 0.0;
  std::vector<double> target_, w3_;
  // The state.
  std::vector<Vec3> pos_;
  double s_out_ = 0.0;
  long iteration_ = 0;
  bool finished_ = false;
  FbaStatus status_;
  std::vector<FbaStatus> history_;
  double seconds_ = 0.0;  // wall time of the iterations so far (all sessions)
  bool built_ = false;    // list_ holds a list (saved with the state: its pair order sets the sums)
  NeighborList list_{0.0};
  std::vector<Vec3> last_move_;  // each sphere's move in the last iteration at the target (momentum)
  // Working memory.
  std::vector<double> outer_;
  std::vector<Vec3> disp_;
};

// Packs spheres of relative radii `relative_radius` into `box` (its periodic axes as given).
// `history_every` > 0 records the convergence; `progress` is called every few iterations.
FbaResult fba_pack(const Box& box, const std::vector<double>& relative_radius, const FbaParams& params, Random& rng,
                   long history_every = 0, const std::function<void(const FbaStatus&)>& progress = {});

// Periodic axes from a name: a subset of "xyz" ("xy", "z", ...) or "none" (InputError otherwise).
std::array<bool, 3> periodic_axes_from_name(const std::string& name);

// Relative radii (size / 2 of each class) of `count` spheres of the given classes
// (largest-remainder counts per class), in a random order drawn from rng.
std::vector<double> fba_class_radii(long count, const SizeClasses& classes, Random& rng);

// Number of spheres of the given classes that fill `volume` to (1 - porosity) when the largest
// class has diameter `max_diameter` [m] (rounded to nearest, >= 1).
long fba_count_for_volume(double volume, double porosity, double max_diameter, const SizeClasses& classes);

// Max relative overlap max (R_i + R_j - d_ij)/(R_i + R_j) over all pairs by brute force over
// every pair and periodic image (O(N^2), for tests), 0 when none overlaps.
double brute_force_max_overlap(const Packing& packing);

}  // namespace packlab::generate
