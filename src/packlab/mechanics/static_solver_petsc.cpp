// The static solver's PETSc backend: rank 0 assembles, every rank holds a block of rows of the
// matrix, of the factor and of the vectors; see static_solver_petsc.hpp.
#include "packlab/mechanics/static_solver_petsc.hpp"

#include <fmt/format.h>
#include <omp.h>
#include <petscksp.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <stdexcept>

#include "packlab/core/error.hpp"
#include "packlab/mechanics/static_stiffness.hpp"

namespace packlab::mechanics::petsc {

namespace {

// What rank 0 announces to the workers (the first of two integers broadcast; the second is the
// factor's id where it names one).
enum Command : int { kFinish = 0, kFactorize = 1, kSolve = 2, kRelease = 3, kMemory = 4 };

struct Process {
  bool started = false, finished = false;
  bool owns_petsc = false;  // PetscInitialize was called here (finish() finalizes)
  int rank = 0, size = 1;
  int next_id = 1;
  std::string error;  // the first message of the PETSc error being handled
};
Process& process() {
  static Process p;
  return p;
}

struct PetscFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// PETSc's error handler: keep the first (innermost) message, print nothing; the caller turns the
// returned code into one message.
PetscErrorCode record_error(MPI_Comm, int, const char*, const char*, PetscErrorCode code, PetscErrorType type,
                            const char* message, void*) {
  if (type == PETSC_ERROR_INITIAL) process().error = message ? message : "";
  return code;
}

void check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  std::string message = process().error;
  process().error.clear();
  if (message.empty()) {
    const char* text = nullptr;
    PetscErrorMessage(code, &text, nullptr);
    message = text ? text : "unknown error";
  }
  throw PetscFailure(fmt::format("static solver: PETSc {} failed: {}", what, message));
}

// An error in the middle of a collective step: the other ranks cannot go on, stop them all.
[[noreturn]] void abort_all(const std::string& message) {
  const Process& p = process();
  if (p.rank == 0)
    std::fprintf(stderr, "packlab: error: %s\n", message.c_str());
  else
    std::fprintf(stderr, "packlab: error (MPI rank %d): %s\n", p.rank, message.c_str());
  std::fflush(stderr);
  MPI_Abort(PETSC_COMM_WORLD, 2);
  std::abort();
}

// Runs rank 0's part of a collective step: with workers, any failure stops every rank (they wait
// in the middle of the step); alone, a PETSc failure is the input's (e.g. a singular matrix).
template <class Step>
void collective(Step&& step) {
  try {
    step();
  } catch (const PetscFailure& e) {
    if (process().size > 1) abort_all(e.what());
    fail_input(e.what());
  } catch (const std::exception& e) {
    if (process().size > 1) abort_all(e.what());
    throw;
  }
}

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

void start() {
  Process& p = process();
  if (p.started) return;
  PetscBool initialized = PETSC_FALSE;
  PetscInitialized(&initialized);
  if (!initialized) {
    // No command-line arguments: packlab's own flags are not PETSc options. PETSC_OPTIONS and
    // --petsc-options are.
    if (PetscInitializeNoArguments() != 0) throw std::runtime_error("static solver: PETSc could not be initialized");
    p.owns_petsc = true;
    std::atexit(finish);
  }
  PetscPushErrorHandler(record_error, nullptr);
  MPI_Comm_rank(PETSC_COMM_WORLD, &p.rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &p.size);
  p.started = true;
}

void announce(Command command, int id) {
  int message[2] = {command, id};
  MPI_Bcast(message, 2, MPI_INT, 0, PETSC_COMM_WORLD);
}

// Rows of each rank: whole particles (6 unknowns each), as evenly as they go.
std::vector<int> rows_per_rank(PetscInt n, int size) {
  const PetscInt particles = n / 6;
  std::vector<int> rows(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r)
    rows[static_cast<std::size_t>(r)] = static_cast<int>(6 * (particles / size + (r < particles % size ? 1 : 0)));
  return rows;
}
std::vector<int> offsets(const std::vector<int>& counts) {
  std::vector<int> start(counts.size(), 0);
  for (std::size_t r = 1; r < counts.size(); ++r) start[r] = start[r - 1] + counts[r - 1];
  return start;
}

// Rows [first, last) of the whole symmetric matrix in compressed rows (sorted columns), from the
// lower triangle in compressed columns: row i is column i's transpose to the left of the
// diagonal (the entries (i, j), j < i, stored in columns j) and column i from the diagonal on.
struct RowBlock {
  std::vector<PetscInt> start, column;
  std::vector<PetscScalar> value;
};
RowBlock row_block(const StiffnessAssembly& a, PetscInt first, PetscInt last) {
  const auto& cs = a.column_start();
  const auto& row = a.row();
  const auto& val = a.values();
  const auto m = static_cast<std::size_t>(last - first);
  RowBlock b;
  b.start.assign(m + 1, 0);
  for (PetscInt j = 0; j < last; ++j)
    for (int k = cs[static_cast<std::size_t>(j)]; k < cs[static_cast<std::size_t>(j) + 1]; ++k) {
      const PetscInt r = row[static_cast<std::size_t>(k)];
      if (j >= first && j < last) ++b.start[static_cast<std::size_t>(j - first) + 1];  // column j from the diagonal
      if (r != j && r >= first && r < last) ++b.start[static_cast<std::size_t>(r - first) + 1];
    }
  for (std::size_t i = 0; i < m; ++i) b.start[i + 1] += b.start[i];
  const auto nnz = static_cast<std::size_t>(b.start[m]);
  b.column.resize(nnz);
  b.value.resize(nnz);
  std::vector<PetscInt> fill(b.start.begin(), b.start.end() - 1);
  // Left parts first (columns j < i, ascending as j runs), then each row's own column.
  for (PetscInt j = 0; j < last; ++j)
    for (int k = cs[static_cast<std::size_t>(j)]; k < cs[static_cast<std::size_t>(j) + 1]; ++k) {
      const PetscInt r = row[static_cast<std::size_t>(k)];
      if (r != j && r >= first && r < last) {
        const auto at = static_cast<std::size_t>(fill[static_cast<std::size_t>(r - first)]++);
        b.column[at] = j;
        b.value[at] = val[static_cast<std::size_t>(k)];
      }
    }
  for (PetscInt i = first; i < last; ++i)
    for (int k = cs[static_cast<std::size_t>(i)]; k < cs[static_cast<std::size_t>(i) + 1]; ++k) {
      const auto at = static_cast<std::size_t>(fill[static_cast<std::size_t>(i - first)]++);
      b.column[at] = row[static_cast<std::size_t>(k)];
      b.value[at] = val[static_cast<std::size_t>(k)];
    }
  return b;
}

// One factorization as every rank holds it.
struct Local {
  Mat matrix = nullptr;
  KSP ksp = nullptr;
  Vec rhs = nullptr, solution = nullptr;
  PetscOptions options = nullptr;  // its own database: PETSC_OPTIONS and the solver's options
  std::vector<int> rows, first;    // per rank
  DistributedSolveInfo info;
  ~Local() {
    if (ksp) KSPDestroy(&ksp);
    if (rhs) VecDestroy(&rhs);
    if (solution) VecDestroy(&solution);
    if (matrix) MatDestroy(&matrix);
    if (options) PetscOptionsDestroy(&options);
  }
};
std::map<int, std::unique_ptr<Local>>& factors() {
  static std::map<int, std::unique_ptr<Local>> f;
  return f;
}

// Every rank: the matrix from its block of rows, the solver from the options, the factorization.
void set_up(Local& f, PetscInt n, RowBlock& block, const std::string& options, int threads) {
  omp_set_num_threads(std::max(1, threads));
  const Process& p = process();
  f.rows = rows_per_rank(n, p.size);
  f.first = offsets(f.rows);
  const PetscInt m = f.rows[static_cast<std::size_t>(p.rank)];
  // The options of this factor in a database of its own, the default while its objects are set
  // up: one solver's options do not leak into the next (the tests run several in one process).
  check(PetscOptionsCreate(&f.options), "PetscOptionsCreate");
  if (const char* environment = std::getenv("PETSC_OPTIONS"))
    check(PetscOptionsInsertString(f.options, environment), "reading PETSC_OPTIONS");
  if (!options.empty()) check(PetscOptionsInsertString(f.options, options.c_str()), "reading the PETSc options");
  check(PetscOptionsPush(f.options), "PetscOptionsPush");
  struct PopOptions {
    ~PopOptions() { PetscOptionsPop(); }
  } pop_options;
  check(MatCreateMPIAIJWithArrays(PETSC_COMM_WORLD, m, m, n, n, block.start.data(), block.column.data(),
                                  block.value.data(), &f.matrix),
        "matrix creation");
  block = RowBlock{};  // copied into the matrix
  check(MatSetOption(f.matrix, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  check(MatSetOption(f.matrix, MAT_SPD, PETSC_TRUE), "MatSetOption");
  check(MatCreateVecs(f.matrix, &f.solution, &f.rhs), "MatCreateVecs");
  check(KSPCreate(PETSC_COMM_WORLD, &f.ksp), "KSPCreate");
  check(KSPSetOperators(f.ksp, f.matrix, f.matrix), "KSPSetOperators");
  // The default: a direct solve, Cholesky by MUMPS; the options database may change any of it.
  check(KSPSetType(f.ksp, KSPPREONLY), "KSPSetType");
  PC pc = nullptr;
  check(KSPGetPC(f.ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  check(KSPSetTolerances(f.ksp, 1e-12, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT), "KSPSetTolerances");
  check(KSPSetErrorIfNotConverged(f.ksp, PETSC_TRUE), "KSPSetErrorIfNotConverged");
  check(KSPSetFromOptions(f.ksp), "KSPSetFromOptions");
  check(KSPSetUp(f.ksp), "set-up (factorization)");
  check(PCSetUp(pc), "factorization");
  KSPType ksp_type = nullptr;
  PCType pc_type = nullptr;
  check(KSPGetType(f.ksp, &ksp_type), "KSPGetType");
  check(PCGetType(pc, &pc_type), "PCGetType");
  const bool factorization = pc_type && (std::strcmp(pc_type, PCCHOLESKY) == 0 || std::strcmp(pc_type, PCLU) == 0);
  f.info.direct = ksp_type && std::strcmp(ksp_type, KSPPREONLY) == 0 && factorization;
  f.info.method = fmt::format("{} + {}", ksp_type ? ksp_type : "?", pc_type ? pc_type : "?");
  if (factorization) {
    MatSolverType solver = nullptr;
    check(PCFactorGetMatSolverType(pc, &solver), "PCFactorGetMatSolverType");
    f.info.method += fmt::format(" ({})", solver ? solver : "petsc");
    if (solver && std::strcmp(solver, MATSOLVERMUMPS) == 0) {
      Mat factor = nullptr;
      check(PCFactorGetMatrix(pc, &factor), "PCFactorGetMatrix");
      PetscInt entries = 0, mb_max = 0, mb_total = 0;
      // INFOG(29): entries in the factors (negative: millions); INFOG(21), (22): megabytes used
      // in the factorization, largest rank and all ranks.
      check(MatMumpsGetInfog(factor, 29, &entries), "MatMumpsGetInfog");
      check(MatMumpsGetInfog(factor, 21, &mb_max), "MatMumpsGetInfog");
      check(MatMumpsGetInfog(factor, 22, &mb_total), "MatMumpsGetInfog");
      f.info.factor_nonzeros =
          entries >= 0 ? static_cast<std::size_t>(entries) : static_cast<std::size_t>(-entries) * 1000000;
      f.info.factor_megabytes_max = static_cast<double>(mb_max);
      f.info.factor_megabytes_total = static_cast<double>(mb_total);
    }
  }
}

// Every rank: scatter b from rank 0, solve, gather x on rank 0.
void solve_local(Local& f, const double* b, double* x) {
  PetscScalar* local = nullptr;
  const int rank = process().rank;
  check(VecGetArray(f.rhs, &local), "VecGetArray");
  MPI_Scatterv(b, f.rows.data(), f.first.data(), MPI_DOUBLE, local, f.rows[static_cast<std::size_t>(rank)], MPI_DOUBLE,
               0, PETSC_COMM_WORLD);
  check(VecRestoreArray(f.rhs, &local), "VecRestoreArray");
  check(KSPSolve(f.ksp, f.rhs, f.solution), "solve");
  const PetscScalar* result = nullptr;
  check(VecGetArrayRead(f.solution, &result), "VecGetArrayRead");
  MPI_Gatherv(result, f.rows[static_cast<std::size_t>(rank)], MPI_DOUBLE, x, f.rows.data(), f.first.data(), MPI_DOUBLE,
              0, PETSC_COMM_WORLD);
  check(VecRestoreArrayRead(f.solution, &result), "VecRestoreArrayRead");
}

double peak_memory() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) * 1024.0;  // kilobytes on Linux
}

std::vector<double> gather_memory() {
  const Process& p = process();
  std::vector<double> all(p.rank == 0 ? static_cast<std::size_t>(p.size) : 0);
  double mine = peak_memory();
  MPI_Gather(&mine, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  return all;
}

// A worker's part of rank 0's factorization `id`.
void factorize_worker(int id) {
  long header[3] = {0, 0, 0};  // unknowns, threads, length of the options
  MPI_Bcast(header, 3, MPI_LONG, 0, PETSC_COMM_WORLD);
  std::string options(static_cast<std::size_t>(header[2]), ' ');
  if (header[2] > 0) MPI_Bcast(options.data(), static_cast<int>(header[2]), MPI_CHAR, 0, PETSC_COMM_WORLD);
  const auto n = static_cast<PetscInt>(header[0]);
  const std::vector<int> rows = rows_per_rank(n, process().size);
  RowBlock block;
  block.start.resize(static_cast<std::size_t>(rows[static_cast<std::size_t>(process().rank)]) + 1);
  MPI_Recv(block.start.data(), static_cast<int>(block.start.size()), MPIU_INT, 0, 1, PETSC_COMM_WORLD,
           MPI_STATUS_IGNORE);
  const auto nnz = static_cast<std::size_t>(block.start.back());
  block.column.resize(nnz);
  block.value.resize(nnz);
  MPI_Recv(block.column.data(), static_cast<int>(nnz), MPIU_INT, 0, 2, PETSC_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_Recv(block.value.data(), static_cast<int>(nnz), MPI_DOUBLE, 0, 3, PETSC_COMM_WORLD, MPI_STATUS_IGNORE);
  auto f = std::make_unique<Local>();
  set_up(*f, n, block, options, static_cast<int>(header[1]));
  factors()[id] = std::move(f);
}

Local& factor_of(int id) {
  const auto it = factors().find(id);
  if (it == factors().end()) throw std::runtime_error(fmt::format("static solver: no PETSc factor {}", id));
  return *it->second;
}

}  // namespace

bool serve_if_worker(int& exit_code) {
  if (!launched_by_mpi()) return false;
  try {
    start();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "packlab: error: %s\n", e.what());
    exit_code = 2;
    return true;
  }
  if (process().rank == 0) return false;
  try {
    for (;;) {
      int message[2] = {kFinish, 0};
      MPI_Bcast(message, 2, MPI_INT, 0, PETSC_COMM_WORLD);
      switch (message[0]) {
        case kFactorize:
          factorize_worker(message[1]);
          break;
        case kSolve:
          solve_local(factor_of(message[1]), nullptr, nullptr);
          break;
        case kRelease:
          factors().erase(message[1]);
          break;
        case kMemory:
          gather_memory();
          break;
        default:
          finish();
          exit_code = 0;
          return true;
      }
    }
  } catch (const std::exception& e) {
    abort_all(e.what());
  }
}

void finish() {
  Process& p = process();
  if (!p.started || p.finished) return;
  p.finished = true;
  if (p.rank == 0 && p.size > 1) announce(kFinish, 0);
  factors().clear();
  if (p.owns_petsc) PetscFinalize();
}

int ranks() { return process().started ? process().size : 1; }

std::vector<double> peak_memory_per_rank() {
  if (!process().started || process().finished) return {peak_memory()};
  std::vector<double> all;
  collective([&] {
    announce(kMemory, 0);
    all = gather_memory();
  });
  return all;
}

DistributedFactor::DistributedFactor(const StiffnessAssembly& matrix, const std::string& options, int threads) {
  try {
    start();
  } catch (const std::exception& e) {
    fail_input(e.what());
  }
  Process& p = process();
  id_ = p.next_id++;
  collective([&] {
    const auto n = static_cast<PetscInt>(matrix.unknowns());
    announce(kFactorize, id_);
    long header[3] = {static_cast<long>(n), static_cast<long>(threads), static_cast<long>(options.size())};
    MPI_Bcast(header, 3, MPI_LONG, 0, PETSC_COMM_WORLD);
    std::string text = options;
    if (!text.empty()) MPI_Bcast(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, PETSC_COMM_WORLD);
    const std::vector<int> rows = rows_per_rank(n, p.size);
    const std::vector<int> first = offsets(rows);
    for (int r = 1; r < p.size; ++r) {
      const auto ru = static_cast<std::size_t>(r);
      const RowBlock block = row_block(matrix, first[ru], first[ru] + rows[ru]);
      MPI_Send(block.start.data(), static_cast<int>(block.start.size()), MPIU_INT, r, 1, PETSC_COMM_WORLD);
      MPI_Send(block.column.data(), static_cast<int>(block.column.size()), MPIU_INT, r, 2, PETSC_COMM_WORLD);
      MPI_Send(block.value.data(), static_cast<int>(block.value.size()), MPI_DOUBLE, r, 3, PETSC_COMM_WORLD);
    }
    RowBlock mine = row_block(matrix, 0, rows[0]);
    auto f = std::make_unique<Local>();
    set_up(*f, n, mine, options, threads);
    info_ = f->info;
    factors()[id_] = std::move(f);
  });
}

DistributedFactor::~DistributedFactor() {
  Process& p = process();
  if (!p.started || p.finished) return;
  collective([&] {
    announce(kRelease, id_);
    factors().erase(id_);
  });
}

void DistributedFactor::solve(const std::vector<double>& b, std::vector<double>& x) {
  collective([&] {
    announce(kSolve, id_);
    solve_local(factor_of(id_), b.data(), x.data());
  });
}

}  // namespace packlab::mechanics::petsc
