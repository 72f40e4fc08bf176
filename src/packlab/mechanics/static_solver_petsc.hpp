// The static solver's distributed backend (`solver_backend = petsc`): the stiffness matrix of
// static_stiffness.hpp factorized and solved by PETSc over MPI, by default a parallel sparse
// Cholesky factorization by MUMPS. Compiled only when packlab is built with PETSc
// (PACKLAB_HAVE_PETSC); this header does not include petsc.h.
//
// Master and workers, so that the command line stays the same under `mpirun -np K packlab ...`:
// rank 0 runs the command (reads the inputs, builds the model, assembles the matrix, writes
// every output); ranks 1..K-1 call serve_if_worker() first thing in main() and wait there for
// rank 0 to announce the collective steps (factorize a matrix, solve, release it, report
// memory, finish). Rank 0 sends each rank its block of rows of the matrix and of the right-hand
// side and gathers the solution: the particle data and the assembled matrix stay on rank 0, the
// factor and the vectors are distributed.
//
// A single process (no MPI launcher) starts PETSc, and with it MPI, only when the first factor
// of this backend is made, so a plain `packlab` run never starts MPI.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace packlab::mechanics {

class StiffnessAssembly;

namespace petsc {

// Under an MPI launcher (mpirun/mpiexec, srun: one of OMPI_COMM_WORLD_SIZE, PMI_SIZE, PMIX_RANK
// set) starts PETSc; on ranks > 0 it then serves rank 0 until rank 0 calls finish() and returns
// true (main() then returns `exit_code`). Returns false on rank 0 and without a launcher.
bool serve_if_worker(int& exit_code);
// Rank 0: releases the workers and finalizes PETSc (and MPI) where this process started them.
// Idempotent; also registered with atexit() when PETSc is started.
void finish();
// The ranks of the solve (1 until PETSc is started).
int ranks();
// Peak resident memory of every rank [bytes] (getrusage), gathered on rank 0. Collective: rank
// 0 announces it to the workers.
std::vector<double> peak_memory_per_rank();

struct DistributedSolveInfo {
  std::size_t factor_nonzeros = 0;  // MUMPS: entries of the factors over all ranks; 0 otherwise
  double factor_megabytes_max = 0.0, factor_megabytes_total = 0.0;  // MUMPS INFOG(21), INFOG(22)
  bool direct = true;  // KSPPREONLY with a factorization: the solve is exact to rounding
  std::string method;  // e.g. "preonly + cholesky (mumps)"
};

// A factorization of `matrix` (its values at construction) on all ranks. `options`: PETSc
// options (e.g. "-ksp_type cg -pc_type gamg") inserted before the defaults are overridden from
// the options database (PETSC_OPTIONS is read too); `threads`: OpenMP/BLAS threads per rank.
class DistributedFactor {
 public:
  DistributedFactor(const StiffnessAssembly& matrix, const std::string& options, int threads);
  ~DistributedFactor();
  DistributedFactor(const DistributedFactor&) = delete;
  DistributedFactor& operator=(const DistributedFactor&) = delete;
  // x = A^-1 b (b, x: one entry per unknown, on rank 0).
  void solve(const std::vector<double>& b, std::vector<double>& x);
  const DistributedSolveInfo& info() const { return info_; }

 private:
  int id_ = 0;
  DistributedSolveInfo info_;
};

}  // namespace petsc
}  // namespace packlab::mechanics
