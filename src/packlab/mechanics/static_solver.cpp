// Sparse Cholesky factorization (CHOLMOD or Eigen) and preconditioned conjugate gradients
// after low-rank changes; see static_solver.hpp.
// GCC 12 reports a false -Wmaybe-uninitialized inside Eigen's AVX-512 kernels (see analyze/fits.cpp).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "packlab/mechanics/static_solver.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>

#include "packlab/core/error.hpp"

#ifdef PACKLAB_HAVE_CHOLMOD
#include <cholmod.h>
#endif
#ifdef PACKLAB_HAVE_PETSC
#include "packlab/mechanics/static_solver_petsc.hpp"
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

#ifdef PACKLAB_HAVE_CHOLMOD
// CHOLMOD's view of the assembled matrix (no copy): symmetric, its lower triangle in sorted
// compressed columns.
cholmod_sparse cholmod_view(const StiffnessAssembly& a) {
  cholmod_sparse A{};
  A.nrow = A.ncol = a.unknowns();
  A.nzmax = a.values().size();
  A.p = const_cast<int*>(a.column_start().data());
  A.i = const_cast<int*>(a.row().data());
  A.x = const_cast<double*>(a.values().data());
  A.stype = -1;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  return A;
}
#endif

}  // namespace

std::vector<std::string> static_solver_backends() {
  std::vector<std::string> backends;
#ifdef PACKLAB_HAVE_CHOLMOD
  backends.push_back("cholmod");
#endif
  backends.push_back("eigen");
#ifdef PACKLAB_HAVE_PETSC
  backends.push_back("petsc");
#endif
  return backends;
}

struct StaticSolver::Factor {
  virtual ~Factor() = default;
  virtual void solve(const std::vector<double>& b, std::vector<double>& x) = 0;
  // r^T A^-1 r (the check of refine()); a factor that can do it with the forward half of a
  // solve overrides this and says so in forward_sweep_norm().
  virtual bool forward_sweep_norm() const { return false; }
  virtual double inverse_norm_squared(const std::vector<double>& r) {
    std::vector<double> z(r.size());
    solve(r, z);
    return std::inner_product(r.begin(), r.end(), z.begin(), 0.0);
  }
  // Whether downdate() is available: downdate(s, ...) changes the factor of A to that of A - s
  // (s positive semi-definite) and keeps the forward half y = L^-1 P b of a solution valid for
  // the new factor and the load b + load_change: `previous_load` is b (the last solve's load);
  // the entries of `load_change` (original order) on the link's unknowns are folded in and set
  // to zero. False when it failed (the factor is then unusable).
  virtual bool can_update() const { return false; }
  // False where solve() is iterative (PETSc with a Krylov method): solve() then checks and refines.
  virtual bool exact() const { return true; }
  virtual bool downdate(const LinkStiffness&, const std::vector<double>& /*previous_load*/,
                        std::vector<double>& /*load_change*/) {
    return false;
  }
  // x = A^-1 b from the kept forward half (the backward sweep only); false when none is kept.
  virtual bool backward_solve(std::vector<double>& /*x*/) { return false; }
  // The kept forward half no longer belongs to the load (it changed elsewhere).
  virtual void drop_forward() {}
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
    cholmod_sparse A = cholmod_view(a);
    factor = cholmod_analyze(&A, &common);
    if (!factor || common.status < CHOLMOD_OK) fail("analysis");
    if (!cholmod_factorize(&A, factor, &common) || common.status != CHOLMOD_OK) {
      if (common.status == CHOLMOD_NOT_POSDEF)
        fail_input("static solver: the stiffness matrix is not positive definite (CHOLMOD)");
      fail("factorization");
    }
    nonzeros = static_cast<std::size_t>(common.lnz);
    bytes = static_cast<std::size_t>(common.memory_inuse);
    // C of a downdate is in the factor's row order: row Perm[k] of A is row k of P A P^T.
    const auto* perm = static_cast<const int*>(factor->Perm);
    permuted_row.resize(a.unknowns());
    for (std::size_t k = 0; k < a.unknowns(); ++k)
      permuted_row[static_cast<std::size_t>(perm[k])] = static_cast<int>(k);
  }
  std::vector<int> permuted_row;
  bool can_update() const override { return true; }
  // A broken link takes its stiffness S out of the matrix: with S = V diag(lambda) V^T (rank <= 6
  // for a link, 12 x 12), A - S = A - C C^T with C = V sqrt(lambda), a rank-r downdate of the
  // factor (Davis & Hager's multiple-rank modification, cholmod_updown) that touches only the
  // columns on the elimination-tree paths of the link's unknowns instead of refactorizing.
  //
  // Sequential linear analysis re-solves after every break: with the forward half y = L^-1 P b
  // carried through the downdate (cholmod_updown_solve touches only the columns on the link's
  // elimination-tree paths), a re-solve is the backward sweep alone, one triangular sweep of
  // the factor instead of two.
  bool downdate(const LinkStiffness& s, const std::vector<double>& previous_load,
                std::vector<double>& load_change) override {
    if (!forward_valid && !start_forward(previous_load)) return false;
    return modify(s, load_change);
  }
  bool backward_solve(std::vector<double>& x) override {
    if (!forward_valid) return false;
    // P A P^T = L D L^T: x = P^T L^-T D^-1 y.
    cholmod_dense* Z = cholmod_solve(CHOLMOD_DLt, factor, forward, &common);
    cholmod_dense* X = Z ? cholmod_solve(CHOLMOD_Pt, factor, Z, &common) : nullptr;
    if (!X) throw std::runtime_error("static solver: CHOLMOD solve failed");
    const auto* xs = static_cast<const double*>(X->x);
    std::copy(xs, xs + x.size(), x.begin());
    cholmod_free_dense(&X, &common);
    cholmod_free_dense(&Z, &common);
    return true;
  }
  void drop_forward() override { forward_valid = false; }
  // The forward half of `load` on the factor turned simplicial LDL^T, as cholmod_updown would
  // turn it (unpacked, so that columns can grow).
  bool start_forward(const std::vector<double>& load) {
    if (!cholmod_change_factor(CHOLMOD_REAL, false, false, false, false, factor, &common)) return false;
    if (forward) cholmod_free_dense(&forward, &common);
    cholmod_dense B = dense_view(load);
    cholmod_dense* Pb = cholmod_solve(CHOLMOD_P, factor, &B, &common);
    forward = Pb ? cholmod_solve(CHOLMOD_L, factor, Pb, &common) : nullptr;
    cholmod_free_dense(&Pb, &common);
    if (!forward) return false;
    if (!load_delta) load_delta = cholmod_zeros(load.size(), 1, CHOLMOD_REAL, &common);
    forward_valid = load_delta != nullptr;
    return forward_valid;
  }
  // The downdate A - S, with the forward half carried along.
  bool modify(const LinkStiffness& s, std::vector<double>& load_change) {
    if (s.size == 0) return true;
    using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 12, 12>;
    // Translations (N/m) and rotations (N m/rad) differ by ~r^2 (1e-14 for a 100 nm particle):
    // decompose the Jacobi-scaled matrix S = D S' D (S'_ii = 1), or the rotational part would
    // drown in the rounding of the translational one (it did: a downdate left an error of 1e-4
    // in the energy norm).
    std::array<double, 12> scale{};
    for (int r = 0; r < s.size; ++r) {
      const double d = s.matrix[static_cast<std::size_t>(13 * r)];
      scale[static_cast<std::size_t>(r)] = d > 0.0 ? std::sqrt(d) : 0.0;
    }
    Small m(s.size, s.size);
    for (int r = 0; r < s.size; ++r)
      for (int c = 0; c < s.size; ++c) {
        const double sr = scale[static_cast<std::size_t>(r)], sc = scale[static_cast<std::size_t>(c)];
        m(r, c) = sr > 0.0 && sc > 0.0 ? s.matrix[static_cast<std::size_t>(12 * r + c)] / (sr * sc) : 0.0;
      }
    const Eigen::SelfAdjointEigenSolver<Small> eigen(m);
    if (eigen.info() != Eigen::Success) return false;
    const auto& lambda = eigen.eigenvalues();
    const double largest = lambda.maxCoeff();
    if (!(largest > 0.0)) return true;
    // Rows of C in the permuted order, sorted (CHOLMOD wants sorted columns).
    std::array<int, 12> order{};
    for (int k = 0; k < s.size; ++k) order[static_cast<std::size_t>(k)] = k;
    std::sort(order.begin(), order.begin() + s.size, [&](int x, int y) {
      return permuted_row[static_cast<std::size_t>(s.unknown[static_cast<std::size_t>(x)])] <
             permuted_row[static_cast<std::size_t>(s.unknown[static_cast<std::size_t>(y)])];
    });
    int rank = 0;
    for (int k = 0; k < s.size; ++k) rank += lambda(k) > 1e-14 * largest ? 1 : 0;
    cholmod_sparse* C =
        cholmod_allocate_sparse(permuted_row.size(), static_cast<std::size_t>(rank),
                                static_cast<std::size_t>(rank * s.size), 1, 1, 0, CHOLMOD_REAL, &common);
    if (!C) return false;
    auto* cp = static_cast<int*>(C->p);
    auto* ci = static_cast<int*>(C->i);
    auto* cx = static_cast<double*>(C->x);
    int column = 0, at = 0;
    for (int k = 0; k < s.size; ++k) {
      if (!(lambda(k) > 1e-14 * largest)) continue;
      const double root = std::sqrt(lambda(k));
      cp[column++] = at;
      for (int e = 0; e < s.size; ++e) {
        const int local = order[static_cast<std::size_t>(e)];
        ci[at] = permuted_row[static_cast<std::size_t>(s.unknown[static_cast<std::size_t>(local)])];
        cx[at++] = scale[static_cast<std::size_t>(local)] * root * eigen.eigenvectors()(local, k);
      }
    }
    cp[column] = at;
    // The load's change on the link's unknowns (the link's own pull on a prescribed neighbour),
    // in the factor's row order; zero elsewhere, and zero again on return.
    auto* delta = static_cast<double*>(load_delta->x);
    for (int e = 0; e < s.size; ++e) {
      const auto u = static_cast<std::size_t>(s.unknown[static_cast<std::size_t>(e)]);
      delta[permuted_row[u]] = load_change[u];
      load_change[u] = 0.0;
    }
    const int ok = cholmod_updown_solve(0, C, factor, forward, load_delta, &common);
    if (!ok) forward_valid = false;
    cholmod_free_sparse(&C, &common);
    return ok && common.status == CHOLMOD_OK;
  }
  cholmod_dense* forward = nullptr;     // y = L^-1 P b of the last solve (factor's row order)
  cholmod_dense* load_delta = nullptr;  // workspace of cholmod_updown_solve, all zero between calls
  bool forward_valid = false;
  [[noreturn]] void fail(const char* what) {
    const int status = common.status;
    release();
    if (status == CHOLMOD_OUT_OF_MEMORY)
      fail_input(fmt::format("static solver: CHOLMOD's {} ran out of memory; try a smaller model", what));
    throw std::runtime_error(fmt::format("static solver: CHOLMOD {} failed (status {})", what, status));
  }
  void release() {
    if (forward) cholmod_free_dense(&forward, &common);
    if (load_delta) cholmod_free_dense(&load_delta, &common);
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
  ~CholmodCholesky() override { release(); }
  static cholmod_dense dense_view(const std::vector<double>& b) {
    cholmod_dense B{};
    B.nrow = b.size();
    B.ncol = 1;
    B.nzmax = b.size();
    B.d = b.size();
    B.x = const_cast<double*>(b.data());
    B.xtype = CHOLMOD_REAL;
    B.dtype = CHOLMOD_DOUBLE;
    return B;
  }
  void solve(const std::vector<double>& b, std::vector<double>& x) override {
    cholmod_dense B = dense_view(b);
    forward_valid = false;
    cholmod_dense* X = cholmod_solve(CHOLMOD_A, factor, &B, &common);
    if (!X) throw std::runtime_error("static solver: CHOLMOD solve failed");
    const auto* xs = static_cast<const double*>(X->x);
    std::copy(xs, xs + x.size(), x.begin());
    cholmod_free_dense(&X, &common);
  }
  // With P A P^T = L D L^T: r^T A^-1 r = y^T D^-1 y for y = L^-1 P r, the forward half of a
  // solve (D = I for LL^T). A downdated factor is simplicial LDL^T (cholmod_updown converts it),
  // whose column j starts with D_jj.
  bool forward_sweep_norm() const override { return true; }
  double inverse_norm_squared(const std::vector<double>& r) override {
    cholmod_dense B = dense_view(r);
    cholmod_dense* Pr = cholmod_solve(CHOLMOD_P, factor, &B, &common);
    cholmod_dense* Y = Pr ? cholmod_solve(CHOLMOD_L, factor, Pr, &common) : nullptr;
    if (!Y) throw std::runtime_error("static solver: CHOLMOD solve failed");
    const auto* y = static_cast<const double*>(Y->x);
    const auto* column = static_cast<const int*>(factor->p);
    const auto* value = static_cast<const double*>(factor->x);
    double sum = 0.0;
    for (std::size_t j = 0; j < r.size(); ++j) sum += factor->is_ll ? y[j] * y[j] : y[j] * y[j] / value[column[j]];
    cholmod_free_dense(&Y, &common);
    cholmod_free_dense(&Pr, &common);
    return sum;
  }
};
#endif

#ifdef PACKLAB_HAVE_PETSC
// PETSc over MPI (static_solver_petsc.hpp): by default MUMPS's parallel Cholesky factorization,
// the factor spread over the ranks. It has no low-rank update: after links are switched off the
// solves run conjugate gradients preconditioned by it (refine()), as with Eigen's factor.
struct PetscFactor final : StaticSolver::Factor {
  petsc::DistributedFactor factor;
  PetscFactor(const StiffnessAssembly& a, const StaticSolverOptions& o) : factor(a, o.petsc_options, o.threads) {
    nonzeros = factor.info().factor_nonzeros;
    bytes = static_cast<std::size_t>(factor.info().factor_megabytes_total * 1e6);
  }
  void solve(const std::vector<double>& b, std::vector<double>& x) override { factor.solve(b, x); }
  bool exact() const override { return factor.info().direct; }
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
#ifdef PACKLAB_HAVE_PETSC
  if (options_.backend == "petsc") factor_ = std::make_unique<PetscFactor>(assembly_, options_);
#endif
  if (!factor_) factor_ = std::make_unique<EigenCholesky>(assembly_);
  omp_set_num_threads(saved_threads);
  stats_.factor_seconds += seconds_since(t0);
  stats_.factor_nonzeros = factor_->nonzeros;
  stats_.factor_bytes = factor_->bytes;
  ++stats_.factorizations;
  matrix_changed_ = false;
  factor_valid_ = true;
  downdates_since_factorization_ = 0;
  pending_downdates_.clear();  // the assembly above has only the active links
}

void StaticSolver::deactivate(std::size_t k) {
  if (!active_[k]) return;
  active_[k] = 0;
  if (!factor_) return;  // the first factorization assembles the active links
  if (options_.modify_factor && factor_valid_ && !matrix_changed_ && factor_->can_update()) {
    // Keep matrix and factor those of the active links: the link leaves the matrix now and
    // the factor at the next solve, which knows the new load (downdate_pending()).
    assembly_.add_link(k, -1.0);
    pending_downdates_.push_back(k);
  } else {
    matrix_changed_ = true;
  }
}

void StaticSolver::downdate_pending(const std::vector<double>& f) {
  if (pending_downdates_.empty()) return;
  const auto t0 = std::chrono::steady_clock::now();
  // The load's change since the last solve: each link's share goes into the factor's kept
  // forward solution with that link's downdate; whatever is left elsewhere (another q or
  // gradient) means a full solve. Without a last load (its solve failed) the forward half
  // starts from f itself.
  const std::vector<double>& previous = last_load_.size() == f.size() ? last_load_ : f;
  std::vector<double> change(f.size());
  for (std::size_t r = 0; r < f.size(); ++r) change[r] = f[r] - previous[r];
  for (std::size_t k : pending_downdates_) {
    const bool ok = factor_->downdate(assembly_.free_link_stiffness(k), previous, change);
    ++downdates_since_factorization_;
    ++stats_.downdates;
    if (!ok) {
      factor_valid_ = false;  // factorize anew
      break;
    }
  }
  pending_downdates_.clear();
  if (std::any_of(change.begin(), change.end(), [](double v) { return v != 0.0; })) factor_->drop_forward();
  stats_.downdate_seconds += seconds_since(t0);
}

double StaticSolver::inverse_norm_squared(const std::vector<double>& r) const {
  require(factor_ != nullptr && r.size() == assembly_.unknowns(), "vector size", static_cast<double>(r.size()),
          fmt::format("{} (the unknowns), after a solve", assembly_.unknowns()));
  return factor_->inverse_norm_squared(r);
}

// Conjugate gradients on the assembled matrix preconditioned by the factor, from x: the
// iterations it took, -1 when it did not reach the tolerance within refactor_iterations.
int StaticSolver::refine(const std::vector<double>& f, std::vector<double>& x) {
  const std::size_t n = assembly_.unknowns();
  auto dot = [](const std::vector<double>& u, const std::vector<double>& v) {
    return std::inner_product(u.begin(), u.end(), v.begin(), 0.0);
  };
  const double fnorm = std::sqrt(dot(f, f));
  if (fnorm == 0.0) {
    std::fill(x.begin(), x.end(), 0.0);
    return 0;
  }
  std::vector<double> r(n), z(n), p(n), Ap(n);
  symmetric_multiply(assembly_, x, Ap);
  for (std::size_t k = 0; k < n; ++k) r[k] = f[k] - Ap[k];
  // Converged when both the residual and the error in the energy norm are small: with the
  // factor M ~ K, r^T M^-1 r ~ e^T K e, the error of the links' deformation energy, against
  // x^T f ~ the energy of the solution. The residual alone is not enough: the stiffness has
  // modes softer than the regularization-free part by many decades (a particle left on one
  // bond), where a residual of 1e-12 |f| after a downdate still left an error of 1e-4 in the
  // energy norm and changed the next break (measured on the 54k-particle opal).
  auto converged = [&](double rz) {
    return std::sqrt(dot(r, r)) <= options_.tolerance * fnorm &&
           !(rz > options_.tolerance * options_.tolerance * std::abs(dot(x, f)));
  };
  // The usual case after a downdate: already converged, checked with half a solve (a factor
  // without it checks with the solve below, whose z the iteration needs anyway).
  if (factor_->forward_sweep_norm() && std::sqrt(dot(r, r)) <= options_.tolerance * fnorm &&
      converged(factor_->inverse_norm_squared(r)))
    return 0;
  factor_->solve(r, z);
  double rz = dot(r, z);
  if (converged(rz)) return 0;
  p = z;
  for (int it = 1; it <= options_.refactor_iterations; ++it) {
    symmetric_multiply(assembly_, p, Ap);
    const double alpha = rz / dot(p, Ap);
    for (std::size_t k = 0; k < n; ++k) {
      x[k] += alpha * p[k];
      r[k] -= alpha * Ap[k];
    }
    ++stats_.pcg_iterations;
    factor_->solve(r, z);
    const double rz_new = dot(r, z);
    const double beta = rz_new / rz;
    rz = rz_new;
    if (converged(rz)) return it;
    for (std::size_t k = 0; k < n; ++k) p[k] = z[k] + beta * p[k];
  }
  return -1;
}

void StaticSolver::solve(std::span<double> q, const DisplacementGradient& gradient) {
  const std::vector<double> f = assembly_.load(q, gradient, active_);
  if (factor_ && factor_valid_) downdate_pending(f);
  if (!factor_ || !factor_valid_) factorize();
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = assembly_.unknowns();
  std::vector<double> x(n, 0.0);
  const int saved_threads = omp_get_max_threads();
  omp_set_num_threads(std::max(1, options_.threads));
  bool solved = true;
  drifted_ = false;
  if (!matrix_changed_) {
    if (factor_->backward_solve(x))
      ++stats_.backward_only_solves;
    else
      factor_->solve(f, x);
    // A downdated factor carries the rounding of its modifications: check the solution on the
    // matrix of the active links and refine (each check_interval-th solve; header comment).
    // So does an iterative solve (PETSc with a Krylov method).
    verified_ = downdates_since_factorization_ == 0 && factor_->exact();
    if (!verified_) {
      const bool check = !factor_->exact() || options_.check_interval <= 1 || strict_solves_ > 0 ||
                         unverified_solves_ + 1 >= options_.check_interval;
      if (check) {
        solved = this->check(f, x) >= 0;
        if (strict_solves_ > 0) --strict_solves_;
        verified_ = true;
      } else {
        ++stats_.unchecked_solves;
      }
    }
  } else {
    // The factor is of the matrix before the links were switched off: precondition with it.
    assembly_.assemble(active_, options_.regularization);
    solved = refine(f, x) >= 0;
    verified_ = true;
  }
  if (!solved) {
    // Too far from the factorized matrix: factorize the current one and solve directly.
    omp_set_num_threads(saved_threads);
    factorize();
    omp_set_num_threads(std::max(1, options_.threads));
    factor_->solve(f, x);
    verified_ = true;
  }
  omp_set_num_threads(saved_threads);
  if (drifted_) strict_solves_ = unverified_solves_ + 1;  // kept for restore()
  unverified_solves_ = verified_ ? 0 : unverified_solves_ + 1;
  assembly_.scatter(x, q);
  last_load_ = f;
  last_solution_ = std::move(x);
  ++stats_.solves;
  stats_.solve_seconds += seconds_since(t0);
}

int StaticSolver::check(const std::vector<double>& f, std::vector<double>& x) {
  const auto t0 = std::chrono::steady_clock::now();
  const int iterations = refine(f, x);
  // Refinement after unchecked solves: the factor drifted somewhere since the last check.
  drifted_ = iterations != 0 && unverified_solves_ > 0;
  ++stats_.checks;
  stats_.check_seconds += seconds_since(t0);
  return iterations;
}

bool StaticSolver::check_last() {
  // Nothing unverified: the last solve was checked, or none was made since restore().
  if (verified_ || unverified_solves_ == 0 || !factor_) return true;
  const auto t0 = std::chrono::steady_clock::now();
  const int saved_threads = omp_get_max_threads();
  omp_set_num_threads(std::max(1, options_.threads));
  std::vector<double> x = last_solution_;
  check(last_load_, x);
  omp_set_num_threads(saved_threads);
  stats_.solve_seconds += seconds_since(t0);
  if (drifted_) {
    strict_solves_ = unverified_solves_ + 1;
    return false;
  }
  verified_ = true;
  unverified_solves_ = 0;
  return true;
}

void StaticSolver::restore(std::span<const std::size_t> reactivated) {
  for (std::size_t k : reactivated) active_[k] = 1;
  // Factorize the active set anew at the next solve (the assembly's values follow it there).
  factor_valid_ = false;
  matrix_changed_ = false;
  pending_downdates_.clear();
  last_load_.clear();
  drifted_ = false;
  verified_ = false;
  unverified_solves_ = 0;
  ++stats_.rollbacks;
}

void StaticSolver::refactorize() {
  factor_valid_ = false;
  matrix_changed_ = false;
  pending_downdates_.clear();  // the next factorization assembles the active links
  last_load_.clear();
  last_solution_.clear();
  verified_ = false;
  drifted_ = false;
  unverified_solves_ = 0;
  strict_solves_ = 0;
}

// bench_static orderings: see the header.
std::vector<OrderingFill> ordering_fill(const StiffnessAssembly& assembly) {
  std::vector<OrderingFill> out;
#ifdef PACKLAB_HAVE_CHOLMOD
  cholmod_common c;
  cholmod_start(&c);
  struct Finish {
    cholmod_common* c;
    ~Finish() { cholmod_finish(c); }
  } finish{&c};
  c.print = 0;
  c.error_handler = nullptr;
  cholmod_sparse A = cholmod_view(assembly);
  const auto analyze = [&](std::string name, const int* perm) {
    const auto t0 = std::chrono::steady_clock::now();
    cholmod_factor* L = perm ? cholmod_analyze_p(&A, const_cast<int*>(perm), nullptr, 0, &c) : cholmod_analyze(&A, &c);
    if (!L) throw std::runtime_error(fmt::format("ordering_fill: CHOLMOD's analysis with {} failed", name));
    out.push_back({std::move(name), c.lnz, c.fl, seconds_since(t0)});
    cholmod_free_factor(&L, &c);
  };
  const std::pair<int, const char*> methods[] = {
      {CHOLMOD_AMD, "AMD"}, {CHOLMOD_METIS, "METIS"}, {CHOLMOD_NESDIS, "NESDIS (CHOLMOD)"}};
  for (const auto& [method, name] : methods) {
    c.nmethods = 1;
    c.method[0].ordering = method;
    analyze(name, nullptr);
  }
  c.nmethods = 0;  // CHOLMOD's default choice (the solver's)
  analyze("default", nullptr);
  const int chosen = c.method[c.selected].ordering;
  for (const auto& [method, name] : methods)
    if (method == chosen) out.back().name = fmt::format("default ({})", name);
  // The particle graph: the pattern of the 6 x 6 blocks, one node per particle.
  const std::size_t particles = assembly.unknowns() / 6;
  std::vector<int> start(particles + 1, 0), index;
  for (std::size_t p = 0; p < particles; ++p) {
    int last = -1;
    for (int k = assembly.column_start()[6 * p]; k < assembly.column_start()[6 * p + 1]; ++k)
      if (assembly.row()[static_cast<std::size_t>(k)] / 6 != last)
        index.push_back(last = assembly.row()[static_cast<std::size_t>(k)] / 6);
    start[p + 1] = static_cast<int>(index.size());
  }
  cholmod_sparse G{};
  G.nrow = G.ncol = particles;
  G.nzmax = index.size();
  G.p = start.data();
  G.i = index.data();
  G.stype = -1;
  G.itype = CHOLMOD_INT;
  G.xtype = CHOLMOD_PATTERN;
  G.dtype = CHOLMOD_DOUBLE;
  G.sorted = G.packed = 1;
  for (const bool nesdis : {false, true}) {
    std::vector<int> perm(particles), cparent(particles), cmember(particles), full(assembly.unknowns());
    if (nesdis)
      cholmod_nested_dissection(&G, nullptr, 0, perm.data(), cparent.data(), cmember.data(), &c);
    else
      cholmod_metis(&G, nullptr, 0, 1, perm.data(), &c);
    // Each particle's six unknowns stay together, in the particle's place.
    for (std::size_t p = 0; p < particles; ++p)
      for (int d = 0; d < 6; ++d) full[6 * p + static_cast<std::size_t>(d)] = 6 * perm[p] + d;
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_GIVEN;
    analyze(nesdis ? "NESDIS on the particle graph" : "METIS on the particle graph", full.data());
  }
#else
  (void)assembly;
#endif
  return out;
}

}  // namespace packlab::mechanics
