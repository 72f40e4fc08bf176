// Brownian-dynamics (BD) coagulation of electrostatically stabilized colloids with the DLVO pair
// potential: the first structure set of doh-elastic-properties (§2.2, Table 2 BD rows, after
// its refs [11, 28], Hütter's BD simulations of coagulating alumina suspensions). docs/bd.md.
//
// Model (every choice a named parameter below, defaults and their sources in docs/bd.md):
//  - N equal spheres of radius a in a periodic cube of edge L = a (4 pi N / (3 Phi))^(1/3)
//    (doh-elastic-properties eq. 5). Start: a random non-overlapping configuration from the
//    force-biased algorithm (generate/fba.hpp) with the spheres inflated by h_0 / 2, so that no
//    two surfaces start closer than `initial_separation` h_0 (beyond the DLVO barrier: the
//    suspension starts stable and dispersed, then coagulates).
//  - Overdamped Langevin equation without hydrodynamic interactions, integrated with the
//    Ermak-McCammon step (Ermak & McCammon, J. Chem. Phys. 69, 1352 (1978), eq. 11 without
//    the diffusion tensor's off-diagonal terms):
//      x_i(t + dt) = x_i(t) + D_0 / (k_B T) F_i dt + sqrt(2 D_0 dt) xi_i,   xi_i ~ N(0, 1)^3,
//    D_0 = k_B T / (6 pi eta a) (Stokes-Einstein). F_i: the DLVO law (dem/contact/dlvo.hpp)
//    of every unbonded pair closer than the cut-off, and the bonds.
//  - Time step: dt = (step_fraction * debye_length)^2 / (2 D_0): the rms Brownian displacement
//    per axis and step is step_fraction of the Debye length, the shortest length on which the
//    potential changes (accuracy rule); or `time_step` given. The deterministic displacement of
//    a particle per step is capped at sqrt(2 D_0 dt): this acts only inside the primary well,
//    where the van der Waals force would otherwise move a sphere by more than the well's width
//    in one step (the fall into the primary minimum is then slowed, never reversed).
//  - Sticking (the irreversible primary minimum): an unbonded pair whose surface separation
//    falls below `bond_separation` is bonded; a bond is a spring on the whole relative position,
//    F_j = -k_b (r_j - r_i - d_0) with d_0 the pair's direction at bonding times
//    2a + bond_separation. Bonded pairs neither slide nor roll on each other: the aggregates are
//    stiff, as the paper says of refs [11, 28]; a cluster translates (free-draining mobility
//    D_0 / n) but does not rotate. With central_bonds the spring acts along the pair only,
//    F_j = -k_b (|d| - |d_0|) d / |d|: bonded spheres roll on each other (the central DLVO well
//    alone), so aggregates restructure until each sphere is held by several bonds. k_b = bond_stiffness_factor * 6 pi
//    eta a / dt (stable explicit steps for up to 12 bonds per sphere at the default 0.05). Bonded pairs feel no DLVO
//    force (the bond replaces it).
//    Between the two, bond_slip_force F_s > 0: the rigid bond resists rolling and sliding up to
//    a tangential force F_s; beyond it the contact point slips (its rest direction d_0 turns
//    towards d until the tangential force is F_s, like a Coulomb slider on the tangential
//    spring), so aggregates hold their shape under thermal forces (k_B T / a ~ 1.6e-14 N) and
//    restructure only where forces exceed F_s. F_s -> 0 approaches the central bond (with a
//    rest length kept along d), F_s -> infinity the rigid one.
//  - At the end, quench_steps steps without the Brownian displacement (time does not advance):
//    the bonds relax from their thermal stretch (sqrt(k_B T / k_b), a few nm) to d_0, so that a
//    later contact criterion (1 + eps) 2a finds every bonded pair (packlab bond --eps 0.01).
//  - Stops at `duration` (in units of the diffusion time a^2 / D_0) or, with until_stable,
//    when the number of bonds grew by less than stable_tolerance (relative) over the last
//    stable_window diffusion times.
//  - Every random number comes from the one generator (core/random.hpp), drawn in particle
//    order every step (on one thread, while the others evaluate pairs). `threads` build the
//    list and evaluate the pairs and bonds, each into its own slot; every sphere then sums its
//    slots in one fixed order, the order of the serial loop (pairs in list order, then bonds
//    in bond order): the same seed gives the same bits at any thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "packlab/core/neighbor_list.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/core/random.hpp"
#include "packlab/dem/contact/dlvo.hpp"

namespace packlab::generate {

inline constexpr double boltzmann_constant = 1.380649e-23;    // k_B [J/K] (SI 2019, exact)
inline constexpr double avogadro_constant = 6.02214076e23;    // N_A [1/mol] (SI 2019, exact)
inline constexpr double elementary_charge = 1.602176634e-19;  // e [C] (SI 2019, exact)

struct BdParams {
  long particles = 1000;                // N
  double volume_fraction = 0.4;         // Phi (doh-elastic-properties Table 1)
  double radius = 0.25e-6;              // a [m] (Table 1)
  double hamaker_constant = 3.67e-20;   // A [J]: Al2O3 / water / Al2O3 (Bergstrom 1997)
  double surface_potential = 0.0;       // psi_0 [V] (0, 12 ... 15 mV in the paper)
  double debye_length = 10.0e-9;        // 1/kappa [m]; replaced by ionic_strength when > 0
  double ionic_strength = 0.0;          // I [mol/m^3] (= mmol/L); 0: use debye_length
  double relative_permittivity = 78.5;  // eps_r of water at 25 C
  double temperature = 298.15;          // T [K]
  double viscosity = 0.89e-3;           // eta [Pa s], water at 25 C
  double min_separation = 0.4e-9;       // h_min of the DLVO law [m]
  double cutoff = 0.25e-6;              // DLVO cut-off separation [m]
  double initial_separation = 30.0e-9;  // h_0: smallest surface gap of the start [m]
  double bond_separation = 1.0e-9;      // pairs closer than this stick [m]
  double bond_stiffness_factor = 0.05;  // k_b dt / (6 pi eta a)
  bool central_bonds = false;           // bonds resist stretching only (spheres roll on each other)
  double bond_slip_force = 0.0;         // [N] tangential force at which a bond's contact point slips; 0: never
  long quench_steps = 200;              // noise-free steps at the end: bonds relax to their rest length
  double step_fraction = 0.1;           // rms Brownian step per axis / Debye length
  double time_step = 0.0;               // [s]; 0: from step_fraction
  double duration = 1.0;                // simulated time / (a^2 / D_0)
  bool until_stable = false;
  double stable_window = 1.0;       // [a^2 / D_0]
  double stable_tolerance = 0.005;  // relative growth of the bond count per window
  long samples = 200;               // rows of the log (and the MSD) over the run
  int threads = 1;                  // neighbour list, pair and bond forces, the update
  void validate() const;            // InputError naming key, value and range

  double kT() const { return boltzmann_constant * temperature; }
  double diffusion_coefficient() const;  // D_0 = k_B T / (6 pi eta a) [m^2/s]
  double diffusion_time() const;         // a^2 / D_0 [s]
  double screening_length() const;       // the Debye length used: from I when given [m]
  double step() const;                   // dt [s]
  dem::Dlvo::Params dlvo() const;        // the pair law's parameters
  double box_edge() const;               // L [m]
};

// The Debye length of a symmetric electrolyte of ionic strength I [mol/m^3]:
// 1/kappa = sqrt(eps_r eps_0 k_B T / (2 N_A e^2 I)) (e.g. Russel, Saville & Schowalter 1989).
double debye_length_from_ionic_strength(double ionic_strength, double relative_permittivity, double temperature);

// The shape of the pair potential U(h) of equal spheres of radius a, from h_min to the cut-off
// (grid search refined by bisection on the force): the barrier (local maximum) and the
// secondary minimum beyond it, in k_B T; has_barrier false when U rises monotonically (no
// local maximum, as for psi_0 = 0).
struct DlvoProfile {
  bool has_barrier = false;
  double barrier_separation = 0.0;          // h of the maximum [m]
  double barrier_kT = 0.0;                  // U(max) / k_B T (unshifted potential, U(inf) = 0)
  double secondary_separation = 0.0;        // h of the secondary minimum [m]
  double secondary_kT = 0.0;                // U(min) / k_B T
  double barrier_above_secondary_kT = 0.0;  // U(max) - U(min), in k_B T
  double cutoff_kT = 0.0;                   // U(cut-off) / k_B T (what the cut-off leaves out)
};
DlvoProfile dlvo_profile(const dem::Dlvo::Params& p, double radius, double kT);

struct BdStatus {
  long step = 0;
  double time = 0.0;          // [s]
  double reduced_time = 0.0;  // t D_0 / a^2
  long bonds = 0;
  long clusters = 0;         // connected components of the bond graph (single spheres count)
  long largest_cluster = 0;  // spheres
  double msd = 0.0;          // mean squared displacement since the start [m^2]
  double seconds = 0.0;      // wall time of the steps so far
};

struct BdResult {
  Packing packing;  // the spheres (wrapped into the box) and the bonds
  BdStatus status;
  bool stable = false;             // stopped by the until_stable criterion
  std::vector<BdStatus> log;       // `samples` rows over the run (and the first and last)
  double time_step = 0.0;          // [s]
  double bond_stiffness = 0.0;     // k_b [N/m]
  double mean_coordination = 0.0;  // 2 bonds / N
};

// The method as a run that can stop and go on (like FbaRun): run() advances by whole steps;
// between two steps save_state() writes everything the next step depends on (parameters,
// positions, wraps, bonds, the random generator, the neighbour list and the log), and a run
// loaded from it continues bit for bit as the uninterrupted one.
class BdRun {
 public:
  // Draws the start from `rng` (force-biased algorithm); InputError on bad input.
  BdRun(const BdParams& params, Random rng);
  static BdRun load_state(std::istream& in, int threads = 0);
  void save_state(std::ostream& out) const;

  // At most `steps` more steps (all that remain when negative); true when the run has ended.
  // `progress` is called at every log row.
  bool run(long steps = -1, const std::function<void(const BdStatus&)>& progress = {});
  bool finished() const { return finished_; }
  const BdStatus& status() const { return status_; }
  const BdParams& params() const { return params_; }
  long total_steps() const { return max_steps_; }
  BdResult result() const;

 private:
  BdRun() = default;
  void setup();
  void step(bool brownian = true);
  void record();  // a log row (clusters, MSD), and the until-stable test
  BdStatus measure() const;
  bool bonded(int i, int j) const;
  void add_bond(int i, int j, const Vec3& d);
  void index_pairs();  // incoming_ from the list (after each rebuild)
  void index_bonds();  // sphere_bonds_ from bonds_ (after setup or load)

  BdParams params_;
  // Derived by setup().
  Box box_;
  dem::Dlvo::Params law_{};
  double dt_ = 0.0, mobility_ = 0.0, noise_ = 0.0, max_drift_ = 0.0, bond_k_ = 0.0, bond_length_ = 0.0;
  double reach2_ = 0.0;  // (2a + cutoff)^2
  long max_steps_ = 0, sample_every_ = 1, window_steps_ = 1;
  std::vector<double> radius_;
  // The state.
  Random rng_{1};
  std::vector<Vec3> pos_, start_;
  std::vector<std::array<int, 3>> wraps_;
  struct Bond {
    int i, j;
    Vec3 rest;  // d_0 [m]
  };
  std::vector<Bond> bonds_;
  static constexpr int max_bonds_per_sphere = 16;
  std::vector<std::array<int, max_bonds_per_sphere>> partners_;
  std::vector<int> partner_count_;
  long step_ = 0;
  long window_bonds_ = 0;  // bonds at the start of the current stability window
  bool finished_ = false, stable_ = false;
  BdStatus status_;
  std::vector<BdStatus> log_;
  double seconds_ = 0.0;
  bool built_ = false;
  NeighborList list_{0.0};
  // Derived from the state (not saved): each sphere's bonds in bond order (its slots of
  // partners_), and for each sphere the listed pairs where it is the partner, in list order.
  std::vector<std::array<int, max_bonds_per_sphere>> sphere_bonds_;
  std::vector<int> incoming_first_, incoming_;
  long indexed_builds_ = -1;  // list_.builds() of incoming_
  // Working memory (sized at setup and at list rebuilds, not in the step).
  struct NewBond {
    int pair;  // listed pair index: list order, the serial loop's order
    Bond bond;
  };
  std::vector<Vec3> force_;       // per sphere (one thread)
  std::vector<Vec3> pair_force_;  // per listed pair: the force on its partner, +0 when it does not act (threads)
  std::vector<Vec3> bond_force_;  // per bond: the force on b.j (threads)
  std::vector<Vec3> normals_;     // the step's normals, three per sphere in sphere order
  std::vector<std::vector<NewBond>> thread_new_bonds_;
  std::vector<NewBond> new_bonds_;
  mutable std::vector<int> parent_, size_;
};

// The slip bond's return mapping: the rest vector d_0 (length L_0) of a bond whose spheres are
// now at d, turned towards d (keeping L_0, in the plane of d_0 and d) just enough that its part
// normal to d is at most max_offset = F_s / k_b; unchanged when it is already within.
Vec3 slip_bond_rest(const Vec3& rest, const Vec3& d, double rest_length, double max_offset);

// Runs the whole method: BdRun(params, Random(seed)).run() and its result.
BdResult brownian_dynamics(const BdParams& params, std::uint64_t seed,
                           const std::function<void(const BdStatus&)>& progress = {});

}  // namespace packlab::generate
