// Lubachevsky–Stillinger growth (scrm-bimodal-packs.txt §3.1): event-driven molecular dynamics
// of hard spheres whose diameters grow linearly in time, in a periodic box, for any number of
// size classes.
//
// Model (every choice is a named parameter below):
//  - Diameters scale together: D_i(t) = D_i^1 s(t), s(t) = s0 + G t. D_i^1 are the diameters
//    that would fill the box (volume fraction 1 at s = 1), so phi(t) = s(t)^3. Starting from
//    points, s0 = 0: a_k(t) = a0_k t as in the paper.
//  - Unit masses, temperature kT = m v_th^2 with the per-component thermal speed v_th equal to
//    the largest diameter D_max^1: the growth rate G is then dimensionless, the rate of growth
//    of the largest diameter in units of D_max^1 per time D_max^1 / v_th.
//  - Collision of i and j (unit normal n from i to j, normal relative speed u = (v_j - v_i).n):
//    the normal components are exchanged (elastic, momentum conserved) and each sphere gets
//    `separation_boost` times the growth speed of the contact distance, sigma_dot = (D_i^1 +
//    D_j^1) G / 2, pushing them apart: u' = -u + 2 b sigma_dot. b >= 1 makes the pair separate
//    faster than the contact distance grows (b = 2 as in Donev–Torquato–Stillinger's and
//    PackingGeneration's codes).
//  - Collision times: the smaller positive root of |dx + dv t| = sigma + sigma_dot t (eq. 8),
//    for the periodic image given by the cell stencil.
//  - Event calendar: one pending event per particle (its earliest collision or neighbour-list
//    transfer) in an indexed binary heap (the heap holds the event times); a predicted collision carries its partner's
//    collision counter and is discarded when the partner's velocity changed since (per-particle invalidation).
//    Particles are advanced lazily (each keeps its own time stamp). A collision later than the partner's own next event
//    is left to the partner (it predicts again then).
//  - Neighbours (Donev, Torquato & Stillinger 2005): each sphere has a bounding sphere, its
//    radius plus `neighbor_skin` x its diameter; spheres are neighbours when their bounding
//    spheres overlap, and only neighbours are tested for collisions. When a sphere reaches its
//    bounding sphere (a transfer event) the bounding sphere is re-centred and the sphere's list
//    rebuilt from a cell grid of bounding-sphere centres (one grid per size class, so small
//    spheres never scan cells sized for large ones). Near jamming spheres rattle far inside
//    their bounding spheres and lists stay valid for whole blocks. The skin adapts per block:
//    larger in the fluid (long free paths), down to 0.5 % of a diameter near jamming, and at
//    most what gives `neighbor_list_limit` neighbours per sphere in an ideal gas of bounding
//    spheres at the block's start and, scaled from the lists the last block ended with, in the
//    dense fluid (which holds more than the gas).
//  - Blocks: after every `events_per_block` x N events all particles are brought to the same
//    time, velocities are rescaled to kT (the boost heats the system), the reduced pressure
//    p = PV/(NkT) of the block is measured from the collision virial (growth part excluded),
//    particles are re-sorted along a Morton curve and all events are predicted anew.
//  - Memory (bench_ls prints it per particle): a particle is one cache line with its class,
//    collision counter and index; cells link their members (a head per cell, a next per
//    particle); the neighbour lists are counted, then laid out with 1 + 1/16 spare entries each,
//    packed in place when relocations leave a thirty-second of the pool unused, and are freed
//    while the particles are re-sorted.
//  - Stops at the target volume fraction (exactly: the last block ends at the time where
//    s^3 = phi), or at jamming: reduced pressure >= max_reduced_pressure (1e12 by default, the
//    criterion of Skoge–Donev and PackingGeneration), or after max_blocks blocks.
//  - The result is checked by an independent pair search: any pair closer than its contact
//    distance has its radii scaled down by that factor (reported; of order 1e-15).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <istream>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "packlab/core/packing.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/size_classes.hpp"

namespace packlab::generate {

struct LsParams {
  double growth_rate = 0.01;             // G = ds/dt (see above); 0 = no growth (equilibration)
  double target_volume_fraction = 0.0;   // stop exactly here; 0 = grow until jammed
  double max_reduced_pressure = 1e12;    // jamming criterion
  double events_per_block = 20.0;        // per particle, between velocity rescalings
  long max_blocks = 0;                   // 0 = no limit
  double max_events_per_particle = 1e7;  // safety limit
  double separation_boost = 2.0;         // b above, >= 1
  double neighbor_skin = 0.1;            // initial bounding sphere = radius + skin x diameter; adapted
                                         // per block so transfers stay 10-50 % of collisions, and
                                         // capped by neighbor_list_limit
  // Largest mean neighbour-list length the skin may give at a block's start, by the ideal-gas
  // count of overlapping bounding spheres; 0 = no limit. Without it the skin of a slow growth from
  // points reaches its upper bound in the dilute gas and the lists hold 23-44 neighbours per
  // sphere at volume fractions 0.05-0.25 (the run's largest memory: 301 bytes per sphere at 10^4,
  // G = 0.04, against 214 with 12; bench_ls, docs/scrm.md). Applied at a block's start (the
  // ideal-gas count) and to the lists a block ends with (the dense fluid's count).
  double neighbor_list_limit = 12.0;
  void validate() const;
};

enum class LsStop { target_reached, jammed, max_blocks, max_events };
std::string ls_stop_name(LsStop stop);

// State after a block (and the final one).
struct LsStatus {
  long blocks = 0;
  long long collisions = 0;
  long long transfers = 0;  // neighbour-list transfers (a sphere reached its bounding sphere)
  long long stale = 0;      // events discarded by the invalidation counters
  double volume_fraction = 0.0;
  double scale = 0.0;             // s
  double reduced_pressure = 1.0;  // of the last block
  double time = 0.0;              // simulated time since the start
  double seconds = 0.0;           // wall time
  double cpu_seconds = 0.0;       // processor time of this process (= wall time on an idle core)
  LsStop stop = LsStop::max_blocks;
  long long events() const { return collisions + transfers; }  // discarded (stale) events not counted
};

class LsSimulation {
 public:
  // Starts from a packing whose spheres do not overlap (beyond round-off); the radii grow in
  // proportion. Any number of distinct radii: particles with equal radii form a class.
  LsSimulation(const Packing& start, const LsParams& params, Random& rng);
  // Starts from points with zero radii (s0 = 0); `unit_radius` are the radii D_i^1 / 2 that
  // fill the box. The box must be periodic on every axis.
  LsSimulation(const Box& box, std::vector<Vec3> points, std::vector<double> unit_radius, const LsParams& params,
               Random& rng);

  // Runs blocks until a stop criterion; on_block is called after each block. Once a criterion
  // other than max_blocks has stopped the simulation, run() returns at once.
  LsStatus run(const std::function<void(const LsStatus&)>& on_block = {});
  // The state between two blocks (as on_block sees it): every particle at one time, positions,
  // velocities, collision counters, the scale, the adapted skin and the status. A simulation
  // loaded from it goes on exactly as the saved one would have (bit for bit).
  void save_state(std::ostream& out) const;
  static LsSimulation load_state(std::istream& in);
  // The packing now (particles in their original order, radii at the current scale, positions
  // wrapped into the box, velocities included). Overlaps are checked: see overlap_correction().
  Packing packing();
  const LsStatus& status() const { return status_; }
  // New parameters (and stop criteria: a stopped simulation may run on).
  void set_params(const LsParams& params);
  const LsParams& params() const { return params_; }
  // 1 - (factor the radii were scaled by in the last packing() to remove overlaps), >= 0.
  double overlap_correction() const { return overlap_correction_; }
  // Replaces positions (e.g. after shaking); same particles, same order as packing().
  void set_positions(const std::vector<Vec3>& position);
  // Bytes held by the simulation's arrays now (their capacities), and the most they held at any
  // time so far, the temporaries of a block's start (re-sort, list build) included.
  std::size_t memory_bytes() const;
  std::size_t peak_memory_bytes() const { return peak_bytes_; }
  // Mean neighbour-list length per sphere now, and the skin in diameters at s_ref = max(s, 0.2)
  // (both as adapted by the last block; bench_ls traces them per block).
  double mean_neighbors() const;
  double neighbor_skin() const { return skin_rel_; }

  // Collision time of two spheres, eq. (8): smallest t >= 0 with |dx + dv t| = sigma + sdot t,
  // where dx, dv are the separation and relative velocity; +inf when they never touch.
  // Overlapping pairs that approach collide at once (t = 0).
  static double collision_time(const Vec3& dx, const Vec3& dv, double sigma, double sigma_dot);
  // Velocities after a collision (unit masses): normal n from i to j, boost b, growth speed sdot.
  static void collide(Vec3& vi, Vec3& vj, const Vec3& n, double sigma_dot, double boost);

 private:
  struct alignas(64) Body {  // one cache line (aligned: a particle is read with one line, not two)
    Vec3 x;                  // position at time t (box coordinates relative to box.lo)
    double t;                // time stamp
    Vec3 v;
    // Collisions so far times 64 plus the size class (< 64; radius at s = 1 is class_rho_[class])
    // in the low six bits. A new stamp invalidates the partners' predictions; those live within
    // one block (every block predicts anew), so a stale one would pass only after exactly 2^26
    // collisions of its partner within a block (of 20 events per sphere).
    // The class needs no word of its own, which leaves the line room for the index (4 B per
    // sphere less, issue #14).
    std::uint32_t stamp;
    int id;  // original index
  };
  static constexpr std::uint32_t class_bits = 6, collision_step = 1u << class_bits;
  static constexpr std::size_t max_classes = collision_step;  // what the stamp's class bits hold
  static int class_of(const Body& b) { return static_cast<int>(b.stamp & (collision_step - 1)); }
  struct SavedBody {  // the checkpoint's layout of a particle (radius at s = 1 in place of class and count)
    Vec3 x;
    double t;
    Vec3 v;
    double rho;
  };
  struct Event {          // the time is the calendar's key (event_time)
    int partner;          // >= 0 collision partner; -1 transfer; -2 none
    std::uint32_t stamp;  // partner's stamp at prediction
  };
  // Neighbour-list entries in one malloc'd block grown by realloc: glibc moves the pages of a
  // large block instead of copying it, so the pool never exists twice while it grows.
  class EntryPool {
   public:
    EntryPool() = default;
    EntryPool(const EntryPool& o) { *this = o; }
    EntryPool(EntryPool&& o) noexcept { swap(o); }
    EntryPool& operator=(const EntryPool& o);
    EntryPool& operator=(EntryPool&& o) noexcept {
      swap(o);
      return *this;
    }
    ~EntryPool() { std::free(p_); }
    void swap(EntryPool& o) noexcept {
      std::swap(p_, o.p_);
      std::swap(n_, o.n_);
    }
    void resize(std::size_t n);  // keeps the first min(n, size()) entries; new ones unset
    void release() {
      std::free(p_);
      p_ = nullptr;
      n_ = 0;
    }
    std::uint32_t* data() { return p_; }
    const std::uint32_t* data() const { return p_; }
    std::size_t size() const { return n_; }
    std::uint32_t& operator[](std::size_t k) { return p_[k]; }

   private:
    std::uint32_t* p_ = nullptr;
    std::size_t n_ = 0;
  };
  struct Grid {
    int n[3] = {1, 1, 1};
    double h[3] = {1, 1, 1};
    std::vector<int> head;  // per cell: first member (-1: empty); next_ links the rest
  };

  LsSimulation() = default;
  void init(const Box& box, std::vector<Vec3> points, std::vector<double> unit_radius, double s0, Random& rng);
  void size_work_arrays();  // the per-particle arrays rebuilt every block
  void start_block();
  bool run_block();  // false when stopped
  void sync_all(double t);
  void build_grids();
  void cell_coords(int i, int c[3]) const;
  int cell_of(int i) const;
  void insert(int i);
  void remove(int i);
  void build_lists();
  template <class Visit>
  void scan_neighbors(int i, bool only_greater, Visit&& visit);
  void add_neighbor(int i, std::uint32_t entry);
  void relocate_list(int i);
  void pack_lists();
  void drop_neighbor(int i, std::uint32_t entry);
  void find_neighbors(int i, bool only_greater);
  void transfer(int i);
  void predict(int i);
  void heap_update(int i, double key);
  void heap_build();
  // Time of i's pending event (the calendar's key; by particle while a block starts).
  double event_time(int j) const { return hkey_[static_cast<std::size_t>(hpos_[j])]; }
  double s_at(double t) const { return s0_ + params_.growth_rate * t; }
  // The scale the skin is relative to: the diameters at s, at least those of s = 0.2 (a growth
  // from points would otherwise start with no skin). skin_[k] = skin_rel_ 2 rho_k skin_scale(s0_).
  static double skin_scale(double s) { return std::max(s, 0.2); }
  double rho_of(const Body& b) const { return class_rho_[class_of(b)]; }

  LsParams params_;
  Box box_;
  Vec3 origin_;
  int nclass_ = 1;
  std::vector<double> class_rho_;  // radius at s = 1 per class
  std::vector<double> reach_;      // nclass x nclass: largest bounding-sphere reach this block
  std::vector<Body> body_;
  std::vector<Event> ev_;
  std::vector<int> next_;          // next member of i's cell (cell_of(i)) in its class grid
  std::vector<Vec3> center_;       // bounding-sphere centres
  std::vector<double> bound_;      // bounding-sphere radii
  std::vector<double> skin_;       // per class: bounding radius - radius at build
  std::vector<double> bound_cap_;  // per class: largest bounding radius this block
  // Neighbour lists: one pool, each particle a segment [base, base + cap) of which fill are
  // used; a full segment moves to the pool's end with 1.5 times the room (list_end_: first free).
  std::vector<std::uint32_t> list_base_;
  std::vector<std::uint16_t> list_fill_, list_cap_;
  EntryPool list_;  // entries j * 32 + image code
  std::size_t list_end_ = 0;
  std::array<Vec3, 27> offset_{};
  std::vector<Grid> grid_;
  std::vector<double> hkey_;
  std::vector<int> hid_, hpos_;
  double s0_ = 0.0, phi1_ = 1.0, v_thermal_ = 1.0;
  double t_end_ = 0.0, t_target_ = 0.0, t_total_ = 0.0;
  bool target_in_block_ = false;
  double virial_ = 0.0;
  double skin_rel_ = 0.1;
  // The bounds of skin_rel_ wherever it is adapted or capped (run_block's end, build_grids).
  static constexpr double min_skin_rel = 0.005, max_skin_rel = 2.0;
  LsStatus status_;
  bool stopped_ = false;  // a stop criterion other than max_blocks was met
  double overlap_correction_ = 0.0;
  std::size_t peak_bytes_ = 0;
  void note_memory(std::size_t temporary_bytes);  // peak_bytes_ = max(peak, now + temporaries)
};

// Random points in a periodic cube and their classes for `particles` spheres of the given
// classes; the cube is sized so that the spheres reach `volume_fraction` when the largest
// radius equals `radius`.
struct LsStart {
  Box box;
  std::vector<Vec3> points;
  std::vector<double> unit_radius;  // fill the box at s = 1
  std::vector<int> klass;
};
LsStart make_ls_start(long particles, const SizeClasses& classes, double radius, double volume_fraction, Random& rng);

}  // namespace packlab::generate
