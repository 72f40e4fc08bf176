// The quasi-static solver of a bonded-particle model: K_ff q_f = -K_fp q_p - B^T D (H d) for the
// free particles' displacements and rotations (static_stiffness.hpp), by a sparse Cholesky
// factorization: CHOLMOD's supernodal LL^T (SuiteSparse, with a fill-reducing ordering and
// BLAS-3 kernels) when packlab was built with it, Eigen's simplicial LL^T (AMD ordering)
// otherwise or on request; in a build with PETSc, on request, PETSc over MPI (MUMPS's parallel
// Cholesky by default; static_solver_petsc.hpp). docs/static-solver.md compares them.
//
// Links switched off after the factorization (sequential linear analysis removing broken
// bonds) change the matrix by a low-rank term (rank <= 6 per link). With CHOLMOD the factor is
// modified in place (a rank-r downdate, cholmod_updown) and each solve is checked against the
// matrix of the active links and refined by conjugate gradients preconditioned with the factor
// (usually zero or one iteration). With `check_interval` k > 1 only every k-th solve after a
// downdate is checked: the others are trusted until the next check, and a check that finds the
// factor drifted (it needed refinement) flags drifted(), upon which the caller rolls back to its
// last verified() solve (restore()). Sequential linear analysis re-solves thousands of times and
// a check costs as much as the solve it checks. Eigen's factor cannot be modified: the next solves run
// preconditioned conjugate gradients on the new matrix with the old factor as the
// preconditioner (in exact arithmetic r + 1 iterations for a change of rank r); so do PETSc's.
// Either way the matrix is factorized anew when the refinement takes more than
// `refactor_iterations`.
//
// Particles with no links at all, and mechanisms of the network (a particle held by one contact
// bond can spin about it), make K singular: a diagonal shift of `regularization` x each diagonal
// entry (x the mean entry of its kind, translation or rotation, where it is zero) keeps it
// positive definite. The loads are orthogonal to those zero-energy modes (K is
// positive semi-definite), so they take no part in the solution and no link force changes.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "packlab/mechanics/static_stiffness.hpp"

namespace packlab::mechanics {

struct StaticSolverOptions {
  std::string backend = "auto";   // "auto" (CHOLMOD when built with it), "cholmod", "eigen", "petsc"
  double regularization = 1e-12;  // relative diagonal shift [-]
  double tolerance = 1e-10;       // PCG: relative residual |r| / |f|
  int refactor_iterations = 40;   // PCG iterations above which the matrix is factorized anew
  bool modify_factor = true;      // CHOLMOD: take switched-off links out of the factor (downdate)
  // Solves after downdates: check every check_interval-th (1: each; see the header comment).
  int check_interval = 1;
  int threads = 1;            // BLAS threads of the CHOLMOD factorization (of each rank with PETSc)
  std::string petsc_options;  // PETSc: options database entries, e.g. "-ksp_type cg -pc_type gamg"
};

// The fill of CHOLMOD's orderings on an assembled matrix (docs/static-solver.md, why the whole
// SLA curve of the 54k opal takes what it takes): AMD, METIS and CHOLMOD's nested dissection on
// the matrix, CHOLMOD's own choice (the solver's), and METIS / nested dissection on the particle
// graph (one node per particle, expanded to its six unknowns). Empty in a build without CHOLMOD.
struct OrderingFill {
  std::string name;
  double factor_nonzeros = 0.0, flops = 0.0, seconds = 0.0;
};
std::vector<OrderingFill> ordering_fill(const StiffnessAssembly& assembly);

// The backends this build has ("cholmod", "eigen", "petsc"; "petsc": static_solver_petsc.hpp).
std::vector<std::string> static_solver_backends();

struct StaticSolverStats {
  std::string backend;
  std::size_t unknowns = 0;
  std::size_t matrix_nonzeros = 0;  // stored (lower triangle)
  std::size_t factor_nonzeros = 0;
  std::size_t matrix_bytes = 0, factor_bytes = 0;
  int factorizations = 0;
  long solves = 0;
  long pcg_iterations = 0;
  long downdates = 0;             // links taken out of the factor by a rank update
  long backward_only_solves = 0;  // solves from the forward half kept through the downdates
  long checks = 0;                // solves after downdates checked against the matrix (refine())
  long unchecked_solves = 0;      // solves after downdates trusted until a later check
  long rollbacks = 0;             // restore() calls: a check found the factor drifted
  double assemble_seconds = 0.0, factor_seconds = 0.0, solve_seconds = 0.0, downdate_seconds = 0.0;
  double check_seconds = 0.0;  // of solve_seconds: the check (and refinement) of solves after downdates
};

class StaticSolver {
 public:
  // `prescribed`: per particle, 1 when its displacement and rotation are given.
  StaticSolver(const StaticLinks& links, std::span<const std::uint8_t> prescribed, const StaticSolverOptions& options);
  ~StaticSolver();
  StaticSolver(const StaticSolver&) = delete;
  StaticSolver& operator=(const StaticSolver&) = delete;

  // Solves for the free particles. q (6 per particle: u, theta): the prescribed particles'
  // entries are read, the free ones written.
  void solve(std::span<double> q, const DisplacementGradient& gradient);
  // Takes link k out of the model (a broken bond) from the next solve on (with CHOLMOD: out
  // of the factor by a downdate at that solve).
  void deactivate(std::size_t k);
  bool active(std::size_t k) const { return active_[k] != 0; }
  const std::vector<std::uint8_t>& active_links() const { return active_; }
  const StaticLinks& links() const { return links_; }
  const StaticSolverStats& stats() const { return stats_; }
  // Whether the last solve is verified: by a fresh factorization, or checked against the matrix
  // of the active links. Only with check_interval > 1 can a solve be unverified.
  bool verified() const { return verified_; }
  // A check (with check_interval > 1) needed refinement after unchecked solves: those may be
  // off, and whatever the caller decided from them since its last verified solve must be redone.
  bool drifted() const { return drifted_; }
  // Checks the last solve now (the end of a run): its verified() after, drifted() when it failed.
  bool check_last();
  // Back to the active set of the last verified solve: `reactivated` are the links deactivated
  // since. The next solve factorizes anew; the solves after it are each checked until past the
  // point where the drift was found.
  void restore(std::span<const std::size_t> reactivated);
  // Factorizes the active links anew at the next solve and forgets the solves before, as a new
  // solver whose links were deactivated before its first solve would: the sequential linear
  // analysis does it at its checkpoints (static_compression.cpp), so that a run resumed from one
  // (a new solver) and the uninterrupted run go on from the same factor, bit for bit.
  void refactorize();
  // r^T K^-1 r by the current factor (r: one entry per unknown, stats().unknowns): the
  // energy-norm measure of the refinement's convergence check, after at least one solve.
  double inverse_norm_squared(const std::vector<double>& r) const;

  struct Factor;  // the factorization of one backend (static_solver.cpp)

 private:
  void factorize();
  // Takes the links deactivated since the last solve out of the factor, carrying its kept
  // forward solution over to the new load f.
  void downdate_pending(const std::vector<double>& f);
  int refine(const std::vector<double>& f, std::vector<double>& x);
  // Checks x against the matrix of the active links and refines it (refine(): its iterations, -1
  // when it failed); sets drifted() when it refined after unchecked solves.
  int check(const std::vector<double>& f, std::vector<double>& x);
  const StaticLinks& links_;
  StaticSolverOptions options_;
  std::vector<std::uint8_t> active_;
  StiffnessAssembly assembly_;
  std::unique_ptr<Factor> factor_;
  bool matrix_changed_ = false;  // links deactivated and not taken out of the factor
  bool factor_valid_ = false;    // false after a failed downdate
  long downdates_since_factorization_ = 0;
  std::vector<std::size_t> pending_downdates_;  // deactivated, still in the factor
  std::vector<double> last_load_;               // the right-hand side of the last solve
  std::vector<double> last_solution_;           // its solution (for check_last())
  bool verified_ = false, drifted_ = false;
  long unverified_solves_ = 0;  // solves since the last verified one
  long strict_solves_ = 0;      // solves after downdates still to be checked each (after restore())
  StaticSolverStats stats_;
};

}  // namespace packlab::mechanics
