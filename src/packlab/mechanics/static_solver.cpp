// Sparse Cholesky factorization (CHOLMOD or Eigen) and preconditioned conjugate gradients
// after low-rank changes; see static_solver.hpp.
// GCC 12 reports a false -Wmaybe-uninitialized inside Eigen's AVX-512 kernels (see analyze/fits.cpp).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "packlab/mechanics/static_solver.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <chrono>
#include <cmath>
#include <numeric>

#include "packlab/core/error.hpp"

#ifdef PACKLAB_HAVE_CHOLMOD
#include <cholmod.h>
#endif

namespace packlab::mechanics {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

using SparseMap = Eigen::Map<const Eigen::SparseMatrix<double, Eigen::ColMajor, int>>;

// y = A x for the symmetric A stored as its lower triangle in compressed columns.
void symmetric_multiply(const StiffnessAssembly& a, const std::vector<double>& x, std::vector<double>& y) {
  const auto& start = a.column_start();
  const auto& row = a.row();
  const auto& value = a.values();
  std::fill(y.begin(), y.end(), 0.0);
  for (std::size_t c = 0; c < a.unknowns(); ++c) {
    const auto b = static_cast<std::size_t>(start[c]), e = static_cast<std::size_t>(start[c + 1]);
    double sum = value[b] * x[c];  // the diagonal entry comes first
    const double xc = x[c];
    for (std::size_t k = b + 1; k < e; ++k) {
      const auto r = static_cast<std::size_t>(row[k]);
      y[r] += value[k] * xc;
      sum += value[k] * x[r];
    }
    y[c] += sum;
  }
}

}  // namespace

std::vector<std::string> static_solver_backends() {
#ifdef PACKLAB_HAVE_CHOLMOD
  return {"cholmod", "eigen"};
#else
  return {"eigen"};
#endif
}

struct StaticSolver::Factor {
  virtual ~Factor() = default;
  virtual void solve(const std::vector<double>& b, std::vector<double>& x) = 0;
  std::size_t nonzeros = 0, bytes = 0;
};

// Eigen's simplicial LL^T with AMD ordering.
struct EigenCholesky final : StaticSolver::Factor {
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double, Eigen::ColMajor, int>, Eigen::Lower, Eigen::AMDOrdering<int>> llt;
  explicit EigenCholesky(const StiffnessAssembly& a) {
    const auto n = static_cast<Eigen::Index>(a.unknowns());
    const SparseMap map(n, n, static_cast<Eigen::Index>(a.values().size()), a.column_start().data(), a.row().data(),
                        a.values().data());
    llt.compute(map);
    if (llt.info() != Eigen::Success)
      fail_input("static solver: the stiffness matrix is not positive definite (Eigen's Cholesky failed)");
    nonzeros = static_cast<std::size_t>(llt.matrixL().nestedExpression().nonZeros());
    bytes = nonzeros * (sizeof(double) + sizeof(int)) + static_cast<std::size_t>(n) * 2 * sizeof(int);
  }
  void solve(const std::vector<double>& b, std::vector<double>& x) override {
    const Eigen::Map<const Eigen::VectorXd> bm(b.data(), static_cast<Eigen::Index>(b.size()));
    Eigen::Map<Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size())) = llt.solve(bm);
  }
};

#ifdef PACKLAB_HAVE_CHOLMOD
// CHOLMOD's supernodal LL^T (its default ordering choice: AMD, METIS when it fills less).
struct CholmodCholesky final : StaticSolver::Factor {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  explicit CholmodCholesky(const StiffnessAssembly& a) {
    cholmod_start(&common);
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.print = 0;
    common.error_handler = nullptr;
    cholmod_sparse A{};
    A.nrow = A.ncol = a.unknowns();
    A.nzmax = a.values().size();
    A.p = const_cast<int*>(a.column_start().data());
    A.i = const_cast<int*>(a.row().data());
    A.x = const_cast<double*>(a.values().data());
    A.stype = -1;  // symmetric, lower triangle stored
    A.itype = CHOLMOD_INT;
    A.xtype = CHOLMOD_REAL;
    A.dtype = CHOLMOD_DOUBLE;
    A.sorted = 1;
    A.packed = 1;
    factor = cholmod_analyze(&A, &common);
    if (!factor || common.status < CHOLMOD_OK) fail("analysis");
    if (!cholmod_factorize(&A, factor, &common) || common.status != CHOLMOD_OK) {
      if (common.status == CHOLMOD_NOT_POSDEF)
        fail_input("static solver: the stiffness matrix is not positive definite (CHOLMOD)");
      fail("factorization");
    }
    nonzeros = static_cast<std::size_t>(common.lnz);
    bytes = static_cast<std::size_t>(common.memory_inuse);
  }
  [[noreturn]] void fail(const char* what) {
    const int status = common.status;
    release();
    if (status == CHOLMOD_OUT_OF_MEMORY)
      fail_input(fmt::format("static solver: CHOLMOD's {} ran out of memory; try a smaller model", what));
    throw std::runtime_error(fmt::format("static solver: CHOLMOD {} failed (status {})", what, status));
  }
  void release() {
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
  ~CholmodCholesky() override { release(); }
  void solve(const std::vector<double>& b, std::vector<double>& x) override {
    cholmod_dense B{};
    B.nrow = b.size();
    B.ncol = 1;
    B.nzmax = b.size();
    B.d = b.size();
    B.x = const_cast<double*>(b.data());
    B.xtype = CHOLMOD_REAL;
    B.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* X = cholmod_solve(CHOLMOD_A, factor, &B, &common);
    if (!X) throw std::runtime_error("static solver: CHOLMOD solve failed");
    const auto* xs = static_cast<const double*>(X->x);
    std::copy(xs, xs + x.size(), x.begin());
    cholmod_free_dense(&X, &common);
  }
};
#endif

StaticSolver::StaticSolver(const StaticLinks& links, std::span<const std::uint8_t> prescribed,
                           const StaticSolverOptions& options)
    : links_(links), options_(options), active_(links.size(), 1), assembly_(links, prescribed) {
  const auto backends = static_solver_backends();
  if (options_.backend == "auto") options_.backend = backends.front();
  if (std::find(backends.begin(), backends.end(), options_.backend) == backends.end())
    fail_input(
        fmt::format("solver_backend = {}: must be one of: auto, {}", options_.backend, fmt::join(backends, ", ")));
  require(options_.regularization >= 0.0 && options_.regularization < 1.0, "regularization", options_.regularization,
          "in [0, 1)");
  stats_.backend = options_.backend;
  stats_.unknowns = assembly_.unknowns();
  if (assembly_.unknowns() == 0) fail_input("static solver: every particle is fixed; nothing to solve for");
}

StaticSolver::~StaticSolver() = default;

void StaticSolver::factorize() {
  auto t0 = std::chrono::steady_clock::now();
  assembly_.assemble(active_, options_.regularization);
  stats_.assemble_seconds += seconds_since(t0);
  stats_.matrix_nonzeros = assembly_.values().size();
  stats_.matrix_bytes = assembly_.bytes();
  t0 = std::chrono::steady_clock::now();
  factor_.reset();
  const int saved_threads = omp_get_max_threads();
  omp_set_num_threads(std::max(1, options_.threads));  // the BLAS of the supernodal kernels
#ifdef PACKLAB_HAVE_CHOLMOD
  if (options_.backend == "cholmod") factor_ = std::make_unique<CholmodCholesky>(assembly_);
#endif
  if (!factor_) factor_ = std::make_unique<EigenCholesky>(assembly_);
  omp_set_num_threads(saved_threads);
  stats_.factor_seconds += seconds_since(t0);
  stats_.factor_nonzeros = factor_->nonzeros;
  stats_.factor_bytes = factor_->bytes;
  ++stats_.factorizations;
  matrix_changed_ = false;
}

void StaticSolver::deactivate(std::size_t k) {
  if (!active_[k]) return;
  active_[k] = 0;
  matrix_changed_ = true;
}

void StaticSolver::solve(std::span<double> q, const DisplacementGradient& gradient) {
  if (!factor_) factorize();
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<double> f = assembly_.load(q, gradient, active_);
  const std::size_t n = assembly_.unknowns();
  std::vector<double> x(n, 0.0);
  const int saved_threads = omp_get_max_threads();
  omp_set_num_threads(std::max(1, options_.threads));
  if (!matrix_changed_) {
    factor_->solve(f, x);
  } else {
    // The factor is of the matrix before the links were switched off: precondition with it.
    auto pcg = [&]() {
      assembly_.assemble(active_, options_.regularization);
      std::vector<double> r = f, z(n), p(n), Ap(n);
      const double fnorm = std::sqrt(std::inner_product(f.begin(), f.end(), f.begin(), 0.0));
      if (fnorm == 0.0) return 0;
      factor_->solve(r, z);
      p = z;
      double rz = std::inner_product(r.begin(), r.end(), z.begin(), 0.0);
      for (int it = 1; it <= options_.refactor_iterations; ++it) {
        symmetric_multiply(assembly_, p, Ap);
        const double alpha = rz / std::inner_product(p.begin(), p.end(), Ap.begin(), 0.0);
        for (std::size_t k = 0; k < n; ++k) {
          x[k] += alpha * p[k];
          r[k] -= alpha * Ap[k];
        }
        ++stats_.pcg_iterations;
        if (std::sqrt(std::inner_product(r.begin(), r.end(), r.begin(), 0.0)) <= options_.tolerance * fnorm) return it;
        factor_->solve(r, z);
        const double rz_new = std::inner_product(r.begin(), r.end(), z.begin(), 0.0);
        const double beta = rz_new / rz;
        rz = rz_new;
        for (std::size_t k = 0; k < n; ++k) p[k] = z[k] + beta * p[k];
      }
      return -1;
    };
    if (pcg() < 0) {
      // Too far from the factorized matrix: factorize the current one and solve directly.
      omp_set_num_threads(saved_threads);
      factorize();
      omp_set_num_threads(std::max(1, options_.threads));
      factor_->solve(f, x);
    }
  }
  omp_set_num_threads(saved_threads);
  assembly_.scatter(x, q);
  ++stats_.solves;
  stats_.solve_seconds += seconds_since(t0);
}

}  // namespace packlab::mechanics
