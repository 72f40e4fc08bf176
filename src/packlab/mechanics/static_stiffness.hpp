// The tangent stiffness of a bonded-particle model, for the quasi-static solver
// (mechanics/static_solver.hpp). Six degrees of freedom per particle, q = (u, theta): the
// displacement of its centre and its small rotation.
//
// Every intact bond (its bond law's BondTangent, dem/bond/bond_law.hpp) and every touching pair
// without a bond (its contact law's PairTangent at the current overlap: Hertz-Mindlin's S_n, S_t,
// the linear law's k_n, k_s; sticking, no slip) is one *link* between particles i and j with
// unit normal n (i to j) and branch lengths b_i, b_j (centre to contact point, as the engine's
// ContactGeometry). Linearizing the engine's kinematics (dem/contact_forces.cpp):
//   relative displacement of the contact points  du = u_j - u_i + b_i n x theta_i + b_j n x theta_j
//                                                     + H d          (H: an imposed affine strain
//                                                                     gradient, d = x_j' - x_i)
//   relative rotation                            dtheta = theta_j - theta_i
//   force on j                                   F = -(k_n du_n n + k_s du_t)
//   moment on j (bonds)                          M = -(k_tor dtheta_n n + k_bend dtheta_t)
//   torque on j = -b_j n x F + M,  on i = -b_i n x F - M, force on i = -F,
// i.e. the engine's incremental shear and moment laws (bpm-inverse-opals eq. 11-15,
// doh-elastic-properties eq. 1-2) for one small increment from a stress-free start. The link's
// energy 1/2 du.D du + 1/2 dtheta.D_theta dtheta (D = k_n nn + k_s (1 - nn), D_theta likewise) gives
// its 12 x 12 stiffness K = B^T D B + R^T D_theta R, assembled into a sparse symmetric matrix.
// By default the forces the links carry before the increment are not included (no geometric
// stiffness): the model is taken as relaxed, as the papers' networks are before loading.
// Optionally (linearize_links(..., prestress = true)) each link also carries its normal force in
// the state linearized, N (tension positive), and its geometric (initial-stress) stiffness is
// added: a force N along the line of centres whose direction n turns with the relative
// displacement of the centres dx = u_j - u_i + H d gives the force on j -(N / L) (1 - nn) dx
// (L = |d|), i.e. K_g = (N / L) [P -P; -P P] on the translations, P = 1 - nn: the geometric
// (stress, initial-stress) stiffness matrix of a pre-loaded bar (truss) element, e.g. Cook,
// Malkus, Plesha & Witt, "Concepts and Applications of Finite Element Analysis", 4th ed. (2002),
// ch. 18 (stress stiffness of a bar). It is also the part -k_n overlap d^2|d|/dd^2 = N P / L of
// the Hessian of the normal spring energy 1/2 k_n overlap^2 that the engine integrates. The force
// stays on the line of centres, which the particles' rotations do not move, so there are no
// rotational entries (no moment-arm terms: its torque about either centre stays zero). Shear
// forces of the pre-stressed state are not included (the set-up the static tests linearize has
// none: the shear histories are not part of a packing file).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "packlab/core/packing.hpp"
#include "packlab/core/vec3.hpp"
#include "packlab/dem/bond/bond_law.hpp"
#include "packlab/dem/engine.hpp"

namespace packlab::mechanics {

// A 3 x 3 displacement gradient H (u = H x), row-major: H[a][b] = du_a / dx_b.
using DisplacementGradient = std::array<std::array<double, 3>, 3>;

// The linearized links of a model (struct of arrays, packing order of particles).
struct StaticLinks {
  std::vector<int> i, j;
  std::vector<Vec3> branch;                    // centre of i to the centre of j's touching image [m]
  std::vector<double> branch_i, branch_j;      // centre to contact point [m]
  std::vector<dem::BondTangent> stiffness;     // contacts: torsion = bending = 0
  std::vector<int> bond;                       // index into packing.bonds, -1 for an unbonded contact
  std::vector<dem::ContactGeometry> geometry;  // bonds: what the bond law's failure_ratio reads
  // Per link, the normal force N it carries in the state linearized [N] (tension positive: the
  // engine's force on j is -N n), for the geometric stiffness (N / |branch|) (1 - nn) on the
  // translations (see above). Empty (the default): no pre-stress term, the stiffness is that of
  // the springs alone. May be scaled or edited after linearize_links.
  std::vector<double> prestress;
  std::size_t size() const { return i.size(); }
  std::size_t bonds() const;
};

// Links of every intact bond and every touching unbonded pair of `packing` under `config`'s
// contact and bond laws (the engine's neighbour search finds the touching pairs). InputError
// when a law has no linearization (e.g. linear_adhesive) or the configuration is invalid.
// `prestress`: also fill StaticLinks::prestress with each link's normal force at the packing's
// state as the engine computes it (its contact_forces(): no shear histories).
StaticLinks linearize_links(const Packing& packing, const dem::EngineConfig& config, bool prestress = false);

// What a link carries for particle displacements q (6 per particle) and an affine gradient H.
struct LinkResponse {
  Vec3 force_on_j;                   // [N] (the force on i is its negative), geometric part included
  Vec3 geometric_force_on_j;         // the pre-stress's part of it, -(N / L) (1 - nn) dx (no torque) [N]
  Vec3 moment_on_j;                  // the bond's moment on j (on i: its negative) [N m]
  double normal_displacement = 0.0;  // du . n: > 0 the pair moves apart [m]
  double energy = 0.0;               // elastic energy of the increment [J] (with the geometric term)
  dem::BondLoad load;                // as the breakage criteria read it (the springs' increment)
};
LinkResponse link_response(const StaticLinks& links, std::size_t k, std::span<const double> q,
                           const DisplacementGradient& gradient);

// The links' forces in the engine's ContactForces form (branch = centre-to-centre vector, force
// on j), for dem::particle_stress. `active`: per link, 0 = left out (removed links); empty = all.
dem::ContactForces link_forces(const StaticLinks& links, std::span<const double> q,
                               const DisplacementGradient& gradient, std::span<const std::uint8_t> active = {});

// The sparse symmetric stiffness matrix over the free degrees of freedom, lower triangle in
// compressed columns (CHOLMOD's and Eigen's layout), with the coupling to the prescribed ones.
// Built once per pattern; values() can be refilled after links are switched off.
// The stiffness of one link over its free unknowns (6 or 12; 6 for a particle bonded to its own
// periodic image or to a prescribed one): `matrix` row-major with leading dimension 12.
struct LinkStiffness {
  int size = 0;
  std::array<int, 12> unknown{};
  std::array<double, 144> matrix{};
};

class StiffnessAssembly {
 public:
  // `prescribed`: per particle, 1 when its six degrees of freedom are given (fixed or driven
  // particles), 0 when they are unknowns. Free particle p's unknowns are 6 free_index(p) + 0..5.
  StiffnessAssembly(const StaticLinks& links, std::span<const std::uint8_t> prescribed);

  // Refills the values with the links whose `active` entry is 1 (empty = all), adding
  // `regularization` x each diagonal entry to it (x the mean diagonal entry of translations or
  // rotations where it is zero).
  void assemble(std::span<const std::uint8_t> active, double regularization);
  // Adds scale x link k's stiffness to the values (scale -1: takes a broken link out of the
  // assembled matrix, keeping the regularization of the last assembly).
  void add_link(std::size_t k, double scale);
  // Link k's stiffness over the free unknowns it touches (a low-rank update of the matrix).
  LinkStiffness free_link_stiffness(std::size_t k) const;
  // Right-hand side of K_ff q_f = f: -K_fp q_p - B^T D (H d) over the active links, for the
  // displacements q (6 per particle; only the prescribed particles' entries are read).
  std::vector<double> load(std::span<const double> q, const DisplacementGradient& gradient,
                           std::span<const std::uint8_t> active) const;
  // Scatters the free unknowns into q (6 per particle; prescribed entries are kept).
  void scatter(std::span<const double> x, std::span<double> q) const;

  std::size_t unknowns() const { return 6 * free_particles_; }
  int free_index(std::size_t particle) const { return free_index_[particle]; }  // -1: prescribed
  const std::vector<int>& column_start() const { return column_start_; }        // size unknowns + 1
  const std::vector<int>& row() const { return row_; }
  const std::vector<double>& values() const { return values_; }
  std::size_t bytes() const;

 private:
  const StaticLinks& links_;
  std::vector<int> free_index_;  // per particle
  std::size_t free_particles_ = 0;
  std::vector<int> column_start_, row_;
  std::vector<double> values_;
  // Per free particle, its neighbours with a larger free index (sorted): the blocks of its
  // columns below the diagonal block.
  std::vector<int> neighbor_start_, neighbor_;
  std::vector<int> link_block_;  // per link: the off-diagonal block's position in its column, -1 none
};

// The 12 x 12 stiffness of link k as four 6 x 6 blocks (ii, ij, ji, jj), row-major.
std::array<std::array<double, 36>, 4> link_stiffness(const StaticLinks& links, std::size_t k);

}  // namespace packlab::mechanics
