// The DEM engine: soft spheres, leap-frog (PFC's central difference) integration of
// translation and rotation, linked-cell + Verlet neighbour list with a skin, contact laws
// from dem/contact/, bond laws from dem/bond/, Cundall local damping, fixed particles. SI units throughout.
//
// Time stepping (central difference, as PFC): forces F(t) from positions x(t), then
//   v(t + dt/2) = v(t - dt/2) + (F(t) + F_d) / m dt,   x(t + dt) = x(t) + v(t + dt/2) dt,
// and the same for the angular velocity with the moment of inertia 2/5 m r^2. Reported
// kinetic energies use the synchronous velocity v(t) = v(t - dt/2) + a(t) dt/2, so that
// kinetic + strain energy is the conserved quantity of the undamped scheme.
//
// OpenMP over particles and contacts. The result does not depend on the thread count: every
// particle's force is summed in the same order whatever the partition (dem/step.cpp), and
// every sum over particles (energies, wall forces) runs over fixed-size chunks.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

#include "packlab/core/neighbor_list.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/core/particle_store.hpp"
#include "packlab/dem/bond/registry.hpp"
#include "packlab/dem/contact/registry.hpp"
#include "packlab/dem/material.hpp"

namespace packlab::dem {

// How the time step is chosen when EngineConfig::time_step is 0.
//   global:   safety * min over all particles of sqrt(m_i / k_i), fixed for the run;
//   contacts: refreshed every step from the contacts present, safety * min over touching
//             pairs of sqrt(m / k) with m the lighter of the two (PFC's practice), capped at
//             max_time_step. Needed when tiny light particles (void particles) would make the
//             global step unusably small while they touch nothing (DESIGN.md numerical notes).
//   stiffness_sum: refreshed every step like `contacts`, but per particle from the sum of its
//             contacts' stiffnesses: safety * min over touching particles of
//             sqrt(m_i / sum_c k_c) (PFC's translational rule; PFC's default safety is 0.8).
//             The step follows the actual loading: a particle with one contact may take a
//             step 1/sqrt(z) of what it takes with z; leap-frog stays stable while
//             dt < sqrt(2 m_i / sum_c k_c) for every particle (Gershgorin bound on the
//             linearized translational dynamics), whatever the coordination.
enum class TimeStepRule { global, contacts, stiffness_sum };

TimeStepRule time_step_rule_from_name(const std::string& name);
std::string time_step_rule_name(TimeStepRule rule);

template <class BondLaw>
using BondMaterialList = std::vector<typename BondLaw::Params>;
// Parameters per bond material for one bond law: the alternative held names the law (a single
// entry applies to every material).
using BondMaterials = BondLaws::variant<BondMaterialList>;

struct EngineConfig {
  std::string contact_law = "linear";  // one of contact_law_names()
  // Parameters per particle type; a single entry applies to every type.
  std::vector<Material> types{Material{}};
  StiffnessRule stiffness_rule = StiffnessRule::particle;
  double time_step = 0.0;         // [s]; 0 = time_step_safety * min_i sqrt(m_i / k_i)
  double time_step_safety = 0.2;  // [-]
  TimeStepRule time_step_rule = TimeStepRule::global;
  // contacts rule: upper bound [s]; 0 = safety * max over particles of sqrt(m_i / k_i)
  // (the step the heaviest particle needs), used while nothing touches.
  double max_time_step = 0.0;
  double skin_ratio = 0.2;  // Verlet skin as a fraction of the largest radius [-]
  // The near list (dem/near_pairs.cpp): the pair loop walks only the listed pairs within the
  // law's range plus a margin of at least this fraction of the skin (more where the particles
  // move fast), refreshed from the Verlet list whenever the particles may have moved half of
  // it. It changes which pairs are visited, never which act: the results are the same bit for
  // bit. 0 = walk every listed pair. In [0, 1].
  double near_margin_ratio = 0.05;
  // Gases (the void expansion method): particles diffuse away from the space-filling-curve
  // order they are given at the start, and neighbours end up far apart in memory (two threads
  // then share most pairs: each thread's particles are spread over the whole box). With this
  // on, a neighbour rebuild renumbers the particles along the curve again when the listed
  // pairs' mean index distance has grown to 1.5 times what it was after the last sort
  // (dem/resort.cpp). Only without bonds (ignored with them). The engine's order
  // (particles(), original_index()) then changes during the run; results stay the same at any
  // thread count and on resume, but not bit for bit those of a run without it.
  bool resort_particles = false;
  // Bonds of the packing's bond list: the bond law and its parameters per bond material.
  // Required when the packing has intact bonds. E.g.
  //   config.bond_materials = BondMaterialList<ElasticBond>{{.youngs_modulus = 6.5e9}};
  BondMaterials bond_materials;
  int threads = 0;  // 0 = OpenMP default
  // With more than one thread: start at one thread; now and then (every `thread_probe_every`
  // seconds, the first time after 300 steps) time stretches of steps at one thread and at
  // `threads`, alternating (other, current, other, current), and run at the faster until the
  // next probe; going up to `threads` needs two probes in a row that agree. On a machine
  // whose cores other jobs use, threads waiting for each other at the step's barriers can make
  // two threads slower than one (docs/engine.md, "Parallelism"). The results do not depend on
  // the thread count, so a switch changes no bit of them.
  bool adapt_threads = true;
  double thread_probe_every = 20.0;   // [s] of running between probes, > 0
  double thread_probe_seconds = 0.1;  // each timed stretch lasts at least this [s] and 10 steps, > 0
};

// The bond law that `materials` holds parameters for ("contact", "elastic").
std::string bond_law_name(const BondMaterials& materials);

// A plane wall: particles on the side the normal points to are pushed back by the contact law
// (the wall is taken to be of the touching particle's material, infinitely large and heavy).
// It moves with a prescribed velocity; the engine records the force the particles exert on it.
struct Wall {
  Vec3 point;            // a point on the plane [m]
  Vec3 normal{0, 0, 1};  // unit normal, pointing into the particles' side
  Vec3 velocity{};       // [m/s]
};

// Names of the registered contact and bond laws (the user-facing strings).
std::vector<std::string> contact_law_names();
std::vector<std::string> bond_law_names();

// A bond failure (a breakage criterion met, eq. 16-17 / the contact bond's strengths): the
// bond's index in the packing's bond list, the time and the bond's midpoint at that step
// (wrapped into the box) [s, m].
struct BondBreak {
  std::size_t bond = 0;
  double time = 0.0;
  Vec3 position{};
};

// Heap bytes an engine holds (vector capacities), by what they store: what `bench_relax` and
// `bench_compress` report per particle and per bond (docs/engine.md "Performance").
struct EngineMemory {
  std::size_t particles = 0;        // state, masses, order, wraps, per-particle sums, bond index
  std::size_t neighbor_list = 0;    // index, the positions and radii at the last build
  std::size_t listed_pairs = 0;     // partners, images, bonded flags (with bonds)
  std::size_t contact_history = 0;  // the contact law's per-pair history (shear springs)
  std::size_t bonds = 0;            // bond list, the bond law's state, order and failure room
  std::size_t threads = 0;          // per-thread crossing lists
  std::size_t total() const { return particles + neighbor_list + listed_pairs + contact_history + bonds + threads; }
};

struct Diagnostics {
  long step = 0;
  double time = 0.0;                    // [s]
  double kinetic_energy = 0.0;          // translational + rotational [J]
  double strain_energy = 0.0;           // elastic energy in contacts [J]
  double unbalanced_force_ratio = 0.0;  // mean |F_i| over free particles / mean |F_c| over contacts
  double mean_coordination = 0.0;       // 2 contacts / particles
  std::size_t contacts = 0;             // touching pairs (overlap > 0)
  double max_overlap_ratio = 0.0;       // max overlap / (r_i + r_j)
  std::size_t intact_bonds = 0;
  std::size_t broken_bonds = 0;  // broken so far (including those broken in the file)
};

// Every force acting between bodies at the current state, as plain arrays (packing order).
// For a particle pair, `branch` is the vector from the centre of i to the centre of j (the
// periodic image that touches) and `force` the force on j (i feels its negative); for a wall
// contact j is -1 - wall index and `branch` goes from the centre to the contact point.
struct ContactForces {
  enum Kind : int { contact = 0, bond = 1, wall = 2 };
  std::vector<int> i, j;
  std::vector<int> kind;
  std::vector<Vec3> branch;  // [m]
  std::vector<Vec3> force;   // [N]
  std::size_t size() const { return i.size(); }
};

// Per-particle Cauchy stress (bpm-inverse-opals eq. 21): sigma_ab = 1/(2 V_p) sum_c l_a F_b
// over the particle's contacts, with l the branch vector to the other centre (twice the
// vector to the contact point, hence the 1/2) and F the force on the particle; tension
// positive. Nine components per particle, row-major, in packing order [Pa].
std::vector<std::array<double, 9>> particle_stress(const ContactForces& forces, const Packing& packing);

// The contact law's state in the engine: parameters per pair of types and the histories of
// the listed pairs and of the particle-wall contacts.
template <class Law>
struct ContactModel {
  Law law;
  int type_count = 1;
  std::vector<typename Law::Params> pair_params;    // [type_i * type_count + type_j]
  std::vector<typename Law::History> history;       // parallel to the neighbour list
  std::vector<typename Law::History> wall_history;  // [particle * walls + wall]
  const typename Law::Params& params(int type_i, int type_j) const { return pair_params[type_i * type_count + type_j]; }
};

using ContactModels = ContactLaws::variant<ContactModel>;

// A law with a central form: evaluate_central gives the normal force of a contact that can
// exert no torque (LinearContact without friction), reading no velocity, spin or history.
template <class Law>
inline constexpr bool has_central_form =
    requires(const ContactGeometry& g, const typename Law::Params& p) { Law::evaluate_central(g, p); };

// The bond law's state: its materials and one history per bond.
template <class Law>
struct BondModel {
  Law law;
  std::vector<typename Law::Params> materials;
  std::vector<typename Law::State> history;  // parallel to the bond list
  const typename Law::Params& params(int material) const {
    return materials.size() == 1 ? materials[0] : materials[static_cast<std::size_t>(material)];
  }
};

using BondModels = BondLaws::variant<BondModel>;

template <class Law>
struct PairBlock;  // dem/step.cpp

class Engine {
 public:
  // Validates the packing and parameters (InputError on bad input) and sets up masses,
  // moments of inertia, the time step and the neighbour list. Per-particle density from the
  // packing wins over the per-type density.
  Engine(const Packing& packing, const EngineConfig& config);

  // Advances n steps.
  void run(long steps);
  // Advances one step and returns the diagnostics of the state at its start.
  Diagnostics step_measured();

  double time_step() const { return dt_; }
  void set_time_step(double dt);
  // safety * min over particles of sqrt(m_i / k_i) for the current particles (global rule).
  double critical_time_step() const;
  // Changes the radius of every particle of `type` (mass and moment of inertia follow at
  // constant density; velocities and contact histories are kept).
  void set_radius_of_type(int type, double radius);
  // Sets every radius (in the packing's particle order).
  void set_radii(const std::vector<double>& radius);
  // Call after editing particles().mass, inverse_mass or inverse_inertia directly, e.g. for
  // mass scaling: refreshes what the engine derives from the masses. (A radius change or a
  // loaded state recomputes the true masses: scale again after them.)
  void masses_changed();

  // The whole dynamic state (particles, contact histories, neighbour list, step, time, time
  // step) in a binary form: an engine built from the same packing and configuration that
  // loads it continues exactly as the saved one would have.
  void save_state(std::ostream& out) const;
  void load_state(std::istream& in);
  long step_count() const { return step_; }
  double time() const { return time_; }
  int threads() const { return tuning_.configured; }  // as configured (0 resolved)
  int active_threads() const { return threads_; }     // this step's (adapt_threads)
  long thread_switches() const { return tuning_.switches; }
  long neighbor_builds() const { return neighbors_.builds(); }
  // Refreshes of the near list, and the pairs it holds now (every listed pair when the pair
  // loop walks them all).
  long near_list_refreshes() const { return near_refreshes_; }
  long particle_resorts() const { return resorts_; }  // resort_particles
  // Renumbers the particles along the space-filling curve now (what resort_particles does at a
  // rebuild when neighbours have drifted apart in memory); histories follow their pairs.
  void sort_particles();
  std::size_t near_pairs() const;
  std::size_t listed_pairs() const { return neighbors_.pair_count(); }
  EngineMemory memory() const;
  std::size_t intact_bonds() const;
  // Axial strain (L - L0) / L0 of every bond (packing's bond order; positive = stretched);
  // NaN for bonds that have failed (relaxing or removed).
  std::vector<double> bond_strains() const;
  // Every bond failure so far, in the order they happened (by bond index within a step).
  const std::vector<BondBreak>& bond_breaks() const { return breaks_; }

  // The forces of every touching pair, intact bond and wall contact at the current state
  // (the stored shear histories; no step is taken and nothing changes).
  ContactForces contact_forces() const;

  // Walls: add before or during a run; index stays valid. Moving a wall: wall(k).velocity.
  std::size_t add_wall(const Wall& wall);
  Wall& wall(std::size_t k) { return walls_.at(k); }
  const Wall& wall(std::size_t k) const { return walls_.at(k); }
  std::size_t wall_count() const { return walls_.size(); }
  // Force the particles exerted on wall k during the last step [N].
  const Vec3& wall_force(std::size_t k) const { return wall_force_.at(k); }
  std::size_t particle_count() const { return particles_.size(); }

  // Particle arrays in the engine's internal order: sorted along a space-filling curve for
  // cache locality. Entry k holds the packing's particle original_index()[k]. A fixed particle
  // (zero inverse mass) keeps whatever velocity it is given here (zero from the constructor):
  // setting one drives it at that velocity, e.g. the grip of a compression test.
  const ParticleStore& particles() const { return particles_; }
  ParticleStore& particles() { return particles_; }
  const std::vector<int>& original_index() const { return original_index_; }
  const Box& box() const { return packing_.box; }
  const EngineConfig& config() const { return config_; }

  // The packing (in its original particle order) with current positions, velocities and
  // angular velocities.
  Packing packing() const;

 private:
  struct Totals {
    std::size_t contacts = 0;
    double contact_force_sum = 0.0;
    double strain_energy = 0.0;
    double max_overlap_ratio = 0.0;
    double kinetic_energy = 0.0;
    double unbalanced_force_sum = 0.0;
    std::size_t free_particles = 0;
    // contacts rule: max over touching pairs of k / m_lighter; stiffness_sum rule: max over
    // particles of sum_c k_c / m_i.
    double max_stiffness_over_mass = 0.0;
    std::size_t bond_breaks = 0;  // bonds that failed this step
    double max_speed2 = 0.0;      // largest |v|^2 after the integration (the near list's drift)
    std::size_t bonds_removed = 0;  // bonds gone this step (their pairs may act from the next)
  };
  // Bonds in the engine's particle order, sorted by owner (bond_first_); `image` is relative to
  // the input frame (see wraps_).
  // Narrow types where the range allows (issue #14: bytes per bond; the constructor refuses
  // an image or material outside them). The listed pair a bond holds is not stored: it is
  // looked up when the neighbour list is rebuilt and when the bond breaks (listed_pair_of).
  struct BondList {
    std::vector<int> i, j;
    std::vector<std::array<std::int16_t, 3>> image;
    std::vector<std::uint16_t> material;
    std::vector<double> rest_length;
    std::vector<std::uint8_t> state;  // 0 intact, 1 broken
  };
  // What one pair or bond contributes to its two particles (zero when it does not act).
  struct Contribution {
    int particle_j = 0;
    Vec3 force_on_j{}, torque_i{}, torque_j{};
    double stiffness = 0.0;
    double energy = 0.0, force_norm = 0.0;  // measured steps only
  };
  // One thread's share: a contiguous range of particles with the pairs and bonds they own.
  // The pairs and bonds that reach a particle of a later range are evaluated first and kept,
  // so that every particle receives its contributions in the order a single thread gives.
  struct ThreadWork {
    int particle_begin = 0, particle_end = 0;
    std::vector<int> crossing_pairs;        // listed pairs, ascending
    std::vector<int> crossing_pair_owners;  // their particle i
    std::vector<Contribution> crossing_pair_results;
    std::vector<std::uint8_t> crossing_pair_acts;  // 1 if the pair acted (touched)
    std::vector<int> crossing_bonds;               // bonds (engine order), ascending
    std::vector<Contribution> crossing_bond_results;
    // Bonds that failed this step (their BondBreak is filled after the force loop: 4 bytes of
    // room per bond of the range instead of a whole BondBreak).
    std::vector<int> failed_bonds;
    // Where each failed bond broke (its midpoint), taken when it failed: with the integration
    // in the force region (pair_forces) the particles move before the region ends. Grows to
    // the most breaks a step has had; a failed allocation is reported after the region.
    std::vector<Vec3> failed_positions;
    bool failed_positions_full = false;
    // Crossing bonds that broke this step, whose listed pair is unflagged after the barrier:
    // before it, other threads may be evaluating that pair, which must still see it bonded
    // (as with one thread). Room for every crossing bond (partition_work).
    std::vector<int> broken_crossing_bonds;
    // The slice of all threads' crossing pairs (concatenated in thread order) that this thread
    // evaluates before the barrier.
    long crossing_slice_begin = 0, crossing_slice_end = 0;
    // The near list's share of this range (dem/near_pairs.cpp): its listed pairs that may act
    // before the next refresh, ascending, and their particle i.
    std::vector<int> near_pairs, near_owners;
    Totals totals;
  };
  template <bool Measure>
  Totals step_impl();
  // Integrate: each thread also advances its own particles at the end of the force region
  // (unmeasured steps: one parallel region per step instead of two).
  template <class Law, bool Measure, bool SumRule, bool Integrate>
  void pair_forces(ContactModel<Law>& model, Totals& totals);
  // Measured steps: integration over fixed chunks with the kinetic energy and force sums.
  void integrate_measured(Totals& totals);
  // Advances particles [begin, end) by one step dt from their forces; returns the largest
  // |v|^2 after the update.
  double advance_particles(int begin, int end, double dt);
  // The contacts and stiffness_sum rules: the time step follows this step's forces.
  bool step_from_forces() const;
  double time_step_from_stiffness(double max_stiffness_over_mass) const;
  void refresh_neighbors();
  // resort_particles: renumbers the particles along the space-filling curve, the neighbour
  // list and every per-particle and per-pair array with them (dem/resort.cpp).
  void resort();
  // The order along the space-filling curve of these positions (r_max: the largest radius),
  // at construction and at every re-sort (dem/resort.cpp).
  std::vector<int> curve_order(const std::vector<Vec3>& position, double r_max) const;
  // adapt_threads: probes and switches between one thread and the configured count before a
  // step (dem/step.cpp).
  void tune_threads();
  void set_active_threads(int threads);
  void mark_bonded_pairs();
  // Splits particles, pairs and bonds among the threads (after every neighbour rebuild and
  // every change of the thread count).
  void partition_work();
  // Each thread's crossing pairs from the pairs it walks (every listed pair of its range, or
  // its near list), then every thread's slice of them all.
  void collect_crossing_pairs();
  // The near list (dem/near_pairs.cpp): refreshed before a step when stale or when the
  // particles may have moved half its margin since the last refresh.
  void refresh_near_pairs();
  bool near_list_due() const;
  // Guarded: the crossing pairs' particles j may be moving (another thread integrating them).
  // Central: the law's evaluate_central (spin_free_ runs of a law that has it): only the
  // positions, radii and masses are gathered, no history is read or written, no torque made.
  template <class Law, bool OneType, bool Indirect, bool Guarded, bool Central>
  void gather_pairs(ContactModel<Law>& model, const int* pairs, const int* owners, int start, int count, int skip_from,
                    const std::uint8_t* crossing_acts, int& crossing_seen, PairBlock<Law>& block);
  template <class Law, bool OneType, bool Measure, bool Central>
  void contact_block(ContactModel<Law>& model, PairBlock<Law>& block);
  template <class BondLaw, bool Measure>
  void bond_contribution(BondModel<BondLaw>& model, std::size_t b, Contribution& out, ThreadWork& work,
                         bool crossing = false);
  // Walls over fixed chunks of particles (inside the parallel region); returns the largest
  // k / m of the wall contacts.
  template <class Law, bool Measure>
  double wall_forces(ContactModel<Law>& model, double* stiffness, double* measure_energy, double* measure_force,
                     std::size_t* wall_contacts);
  std::array<int, 3> bond_image_now(std::size_t b) const;
  // The neighbour-list pair that bond b's two particles (at its image) form, or -1 if they are
  // not listed (farther apart than the list reaches).
  int listed_pair_of(std::size_t b) const;
  // From bond b's particle i to the image of its particle j that it holds, now.
  Vec3 bond_vector(std::size_t b) const;
  void update_mass(std::size_t k);
  double heaviest_particle_time_step() const;
  // What the laws read about the pair (i, j) whose touching image of j sits at x_i + d
  // (|d| = distance > 0), and about particle k touching a wall at `distance` from it.
  ContactGeometry pair_geometry(std::size_t i, std::size_t j, const Vec3& d, double distance) const;
  ContactGeometry wall_geometry(std::size_t k, const Wall& wall, double distance) const;
  const Material& params_of_type(int type) const;

  // The input's box and extra fields only: its per-particle arrays and bonds are moved into
  // particles_ and bonds_ (in the engine's order) and rebuilt by packing(), so the engine does
  // not hold the model twice (issue #14: bytes per particle and per bond).
  Packing packing_;
  bool input_has_density_ = false, input_has_fixed_ = false;  // packing() gives them back
  EngineConfig config_;
  ParticleStore particles_;
  std::vector<double> type_damping_;  // local damping alpha per particle type
  std::vector<int> original_index_;
  // Per particle [kg/m^3] only when the input packing gives densities; empty otherwise (each
  // type's density applies: issue #14, bytes per particle).
  std::vector<double> density_;
  // Box lengths each particle was wrapped by since the input: unwrapped = position + wraps L.
  std::vector<std::array<int, 3>> wraps_;
  BondList bonds_;
  // Per neighbour pair: the contact law is off (a bond holds the pair). Empty without bonds.
  std::vector<std::uint8_t> pair_bonded_;
  std::size_t broken_bonds_ = 0;
  std::vector<BondBreak> breaks_;
  std::vector<Wall> walls_;
  std::vector<Vec3> wall_force_;  // per wall, last step
  NeighborList neighbors_;
  // bonds_ is sorted by owner (the smaller of the two particle indices), then by input index:
  // bonds bond_first_[k] .. bond_first_[k + 1] - 1 are the bonds owned by particle k, and
  // bond_input_index_[b] is bond b's index in the packing's bond list (the API's bond index:
  // breaks, strains, packing(), checkpoints). Both empty without bonds.
  std::vector<int> bond_input_index_, bond_first_;
  std::vector<int> partition_first_cut_;  // partition_work's scratch (kept: it runs at every rebuild)
  ContactModels model_;
  BondModels bond_model_;
  std::vector<ThreadWork> work_;       // per thread (dem/step.cpp)
  // The near list (dem/near_pairs.cpp): its margin beyond the law's range [m] (0: off), whether
  // the pair loop walks it (else every listed pair), whether it must be refreshed before the
  // next step, and a bound on how far any particle moved since its refresh [m].
  double near_margin_ = 0.0;       // of the current near list
  double near_base_margin_ = 0.0;  // near_margin_ratio x skin: the least margin
  double last_max_speed_ = 0.0;    // the largest |v| after the last step [m/s]
  bool near_active_ = false, near_stale_ = true;
  double near_drift_ = 0.0;
  // No contact can exert a torque (a law's torque_free for every pair of types, e.g. linear
  // contacts without friction) and there are no bonds: the integration skips the spins, which
  // stay as they are (issue #14: the void expansion method's integration reads a third less).
  bool spin_free_ = false;
  // The listed pairs keep the contact law's history (ContactModel::history). Not in spin_free_
  // runs of a law with a central form: no pair reads or writes one there, so none is stored,
  // carried over at a rebuild, re-sorted or checkpointed (issue #14: 24 bytes per listed pair
  // in the void expansion method's engine; the wall contacts keep theirs).
  bool pair_histories_ = true;
  long near_refreshes_ = 0;
  // resort_particles: the listed pairs' mean index distance after the last sort (0: not yet
  // measured), and the sorts so far.
  double sorted_index_distance_ = 0.0;
  long resorts_ = 0;
  std::vector<double> stiffness_sum_;  // stiffness_sum rule: per particle [N/m]
  // Measured steps: per particle, the strain energy and contact force magnitudes of the
  // contacts it owns, summed in particle order afterwards (the same sums at any thread count).
  std::vector<double> measure_energy_, measure_force_;
  std::vector<double> chunk_sums_;      // per fixed-size chunk of particles
  std::vector<double> chunk_max_speed2_;  // measured steps: per chunk, the largest |v|^2
  std::vector<Vec3> wall_chunk_force_;  // [chunk * walls + wall]
  int threads_ = 1;                     // this step's thread count
  struct ThreadTuning {
    int configured = 1;  // config.threads (0 resolved to the OpenMP default)
    int best = 1;        // the faster of 1 and configured at the last probe
    // 0: running at best; 1 and 3: timing the other count; 2 and 4: timing best.
    int phase = 0;
    long steps_to_probe = 0;  // before the first probe
    std::chrono::steady_clock::time_point next_probe{}, phase_start{};
    long phase_steps = 0;
    double other_seconds = 0.0, best_seconds = 0.0;  // summed over the probe's stretches
    long other_steps = 0, best_steps = 0;
    bool confirming = false;  // this probe repeats one that favoured more threads
    long switches = 0;
    static constexpr long untimed_steps = 2;  // after each switch
  } tuning_;
  double dt_ = 0.0;
  double time_step_cap_ = 0.0;  // contacts rule: max_time_step or the heaviest particle's step
  long step_ = 0;
  double time_ = 0.0;
};

}  // namespace packlab::dem
