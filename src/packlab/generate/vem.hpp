// The void expansion method (VEM), vem-void-expansion-method §2.2 (docs/vem.md).
//
//  1. A periodic cube of edge l = r_S (4 pi N_S / (3 Phi_S))^(1/3) (eq. 3).
//  2. N_S structural particles (type 0) at uniform random positions with radius r_S/(m+1) and
//     N_V void particles (type 1) at uniform random positions with radius r_V0 (0.005 r_S).
//  3. Blow-up: m times, the structural radius grows by r_S/(m+1), each followed by a relaxation;
//     after the m-th step it is exactly r_S.
//  4. Expansion cycles: record a row of the CN(q) curve (q = r_V/r_S, the mean coordination
//     number of the structural particles alone with the contact distance (1+eps) 2 r_S, the
//     total volume fraction Phi_T = Phi_S (1 + q^3 n) of eq. 5, energies, relaxation steps),
//     stop if stage III is reached or q would pass max_q, else grow the void radius by r_V0 and
//     relax.
//  5. At the end the void particles are dropped: structural_packing().
//
// DEM: linear contacts (eq. 1-2, particle stiffnesses in series), friction 0, Cundall local
// damping 0.7, the time step refreshed every step from the touching pairs (TimeStepRule
// contacts, DESIGN.md "time step in quasi-static generation").
//
// Relaxation ("equilibration" in the paper; it does not state its criterion): DEM steps until,
// at a check every `relax_check_interval` steps, either
//  - the forces balance: the unbalanced force ratio of the touching particles
//    (touching_unbalanced_force_ratio, PFC's "solve ratio" restricted to particles in contact)
//    is below `relax_tolerance` (how stage III ends its relaxations), or
//  - the overlaps are gone: no contact overlaps by more than `relax_overlap` (r_i + r_j) (how
//    stage I and II end theirs: an increment opens overlaps up to r_V0 / (r_V + r_S) ~ 1e-3,
//    which the unjammed packing removes by rearranging; near the transition creeping particles
//    keep touching with vanishing forces and the force ratio alone would not fall),
// at most `relax_max_steps` steps.
//
// Stage III (the stop criterion): the strain energy per structural particle relative to
// k_n,S r_S^2, e = E_strain / (N_S k_n,S r_S^2), reaches `stop_strain_energy` after a
// relaxation. In stage I and II the relaxed packing holds almost no elastic energy (e ~ 1e-8
// to 1e-6); once the structure is jammed every increment of r_V compresses it and e grows by
// orders of magnitude within a few cycles.
//
// Void mass scaling (reported; docs/vem.md shows the curve does not depend on it): a void
// particle of radius 0.005 r_S at density rho_S/10 has 1e-8 of a structural mass, so the
// contacts time step would fall ~4000-fold whenever a small void touches something. Each void
// particle therefore gets the mass max(m_V, c m_S k_V / k_S) (moment of inertia 2/5 m r^2),
// with k_V, k_S the stiffest contacts a void and a structural particle can form, so that with
// c = 1 a void's critical step is never below a structural one; c = `void_mass_scaling`,
// 0 switches scaling off. With the Table 1 stiffnesses scaling stops at q = (c 10 k_V/k_S)^(1/3)
// (q = 1.22 for c = 1): the voids carry their true mass near and above the inflection.
//
// Checkpoints: save_checkpoint() writes the whole state (parameters, random generator, stage,
// cycle, relaxation progress, the curve and the engine state); a Vem built from it continues
// bit for bit as the saved one would have (same thread count). The state is checksummed: a
// damaged file is an InputError, never a crash or a silently different run.
#pragma once

#include <cstdint>
#include <functional>
#include <istream>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "packlab/core/packing.hpp"
#include "packlab/core/random.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/dem/material.hpp"

namespace packlab::generate {

struct VemParams {
  long structural = 8000;            // N_S [-]
  long voids = 2000;                 // N_V [-]
  double phi_s = 0.4;                // Phi_S, volume fraction of the structural particles [-]
  double radius = 2.5e-7;            // r_S [m]
  int blowup_steps = 10;             // m [-]
  double void_radius_ratio = 0.005;  // r_V0 / r_S, initial void radius and its growth per cycle [-]
  // Table 1 (§3: k_n,S = 1e3, k_s,S = 1e-2, k_n,V = 1e2, k_s,V = 1e-2 N/m, rho_V = rho_S/10).
  dem::Material structural_material{1.0e3, 1.0e-2, 0.0, 3690.0, 0.7};
  dem::Material void_material{1.0e2, 1.0e-2, 0.0, 369.0, 0.7};
  double contact_eps = 0.01;         // CN contact distance (1 + eps) 2 r_S [-]
  double relax_tolerance = 1e-2;     // unbalanced force ratio ending a relaxation [-]
  double relax_overlap = 1e-5;       // ... or largest overlap / (r_i + r_j) ending it [-]
  long relax_max_steps = 20000;      // step limit of one relaxation
  long relax_check_interval = 25;    // steps between two checks
  double void_mass_scaling = 1.0;    // c (see above); 0 = no scaling [-]
  double stop_strain_energy = 1e-3;  // stage III: E_strain / (N_S k_n,S r_S^2) [-]
  double max_q = 3.0;                // last q recorded at most [-]
  // Stage III ends a run only once CN has reached this as well (0 = no minimum): the
  // structures of doh-elastic-properties Table 2 share C = 4.6-4.7 whatever n, while the
  // stage III stop leaves CN = 4.0-5.6 (docs/reproduction.md tests this unstated end point).
  double stop_min_coordination = 0.0;  // [-]
  // Time step: PFC's rule (the paper's code) by default, safety * min_i sqrt(m_i / sum of the
  // contact stiffnesses of i) refreshed every step; docs/vem.md shows how the step changes q_i.
  std::string time_step_rule = "stiffness_sum";  // dem::TimeStepRule name except "global"
  double time_step_safety = 0.8;                 // fraction of sqrt(m/k) [-]
  double skin = 0.2;                             // Verlet skin / r_S [-]
  int threads = 0;                               // OpenMP threads, 0 = all; results are bitwise reproducible per count
  bool adapt_threads = true;                     // dem::EngineConfig::adapt_threads
  std::uint64_t seed = 1;

  // InputError naming the first bad key (impossible Phi_S, box too small for max_q, ...).
  void validate() const;
  double number_ratio() const { return static_cast<double>(voids) / static_cast<double>(structural); }
};

// Box edge of eq. 3: l = r_S (4 pi N_S / (3 Phi_S))^(1/3) [m].
double vem_box_edge(long structural, double radius, double phi_s);

// One row of the CN(q) curve, recorded before each increment of the void radius.
struct VemRow {
  long cycle = 0;                       // 0 = right after the blow-up
  double q = 0.0;                       // r_V / r_S
  double cn = 0.0;                      // mean coordination number of the structural particles alone
  double phi_total = 0.0;               // Phi_S (1 + q^3 n), eq. 5
  double strain_energy = 0.0;           // all contacts [J]
  double kinetic_energy = 0.0;          // all particles, scaled void masses [J]
  long steps = 0;                       // relaxation steps that led to this state
  double unbalanced_force_ratio = 0.0;  // at the end of that relaxation
  bool converged = false;               // that relaxation met the tolerance (else: step limit)
};

enum class VemStage { blowup, expansion, finished };
enum class VemStop { none, stage_three, max_q };
std::string vem_stop_name(VemStop stop);

// The relaxation criterion: mean |F_i| over the particles that touch something (F_i != 0)
// divided by the mean contact force, from the forces of the step `d` measured (the engine's own
// ratio averages over every free particle, which in a dilute packing with few contacts is
// small however unbalanced those contacts are). 0 when nothing touches.
double touching_unbalanced_force_ratio(const dem::Engine& engine, const dem::Diagnostics& d);

// The structural particles (type 0) of a packing, in their order.
Packing structural_only(const Packing& packing);
// Mean coordination number of the structural particles alone: contacts at centre distance
// below (1 + eps)(r_i + r_j) = (1 + eps) 2 r_S between structural particles only.
double structural_coordination(const Packing& packing, double eps);

class Vem {
 public:
  // Places the particles (draws from a Random seeded with params.seed) and sets up the engine.
  explicit Vem(const VemParams& params);
  // Continues from a checkpoint written by save_checkpoint(); `threads` > 0 overrides the saved
  // thread count (the run then stays valid but is no longer bitwise equal to one without the break),
  // `adapt_threads` the saved dem::EngineConfig::adapt_threads (it changes no result).
  static std::unique_ptr<Vem> resume(std::istream& checkpoint, int threads = 0,
                                     std::optional<bool> adapt_threads = std::nullopt);
  ~Vem();
  Vem(const Vem&) = delete;
  Vem& operator=(const Vem&) = delete;

  // Runs at most `max_steps` DEM steps (< 0: no limit); returns finished().
  bool run(long max_steps = -1);
  bool finished() const { return stage_ == VemStage::finished; }

  void save_checkpoint(std::ostream& out) const;

  // Called after each recorded row (progress, snapshots via structural_packing()).
  std::function<void(const VemRow&)> on_row;
  // Called at each relaxation check with the steps of this run so far (progress, checkpoints).
  std::function<void(const dem::Diagnostics&)> on_check;

  const VemParams& params() const { return params_; }
  const std::vector<VemRow>& curve() const { return curve_; }
  VemStage stage() const { return stage_; }
  VemStop stop_reason() const { return stop_; }
  int blowup_done() const { return blowup_done_; }
  long cycle() const { return cycle_; }
  long total_steps() const { return total_steps_; }
  long limited_relaxations() const { return limited_relaxations_; }
  double structural_radius() const;
  double void_radius() const;
  double box_edge() const { return vem_box_edge(params_.structural, params_.radius, params_.phi_s); }
  // Void masses: true mass, and the mass each void had after scaling (current state).
  double void_mass_floor() const;
  // All particles (structural first, then voids) and the structural ones alone, current state.
  Packing packing() const;
  Packing structural_packing() const;
  const dem::Engine& engine() const { return *engine_; }
  // Wall-clock seconds spent in run() over all sessions (saved in checkpoints).
  double seconds() const { return seconds_; }

 private:
  struct ResumeTag {};
  void save_state(std::ostream& out) const;  // the checksummed part of save_checkpoint()
  Vem(const VemParams& params, ResumeTag);
  void build_engine();
  void apply_mass_scaling();
  void start_relaxation();
  void finish_relaxation();
  void record_row();
  dem::EngineConfig engine_config() const;

  VemParams params_;
  Random rng_;
  std::unique_ptr<dem::Engine> engine_;
  VemStage stage_ = VemStage::blowup;
  VemStop stop_ = VemStop::none;
  int blowup_done_ = 0;    // blow-up steps applied
  long cycle_ = 0;         // void increments applied
  bool relaxing_ = false;  // a relaxation is in progress
  long relax_done_ = 0;    // its steps so far
  dem::Diagnostics relax_last_{};
  bool relax_converged_ = false;
  long total_steps_ = 0;
  long limited_relaxations_ = 0;
  double seconds_ = 0.0;
  std::vector<VemRow> curve_;
};

}  // namespace packlab::generate
