// The static solver's PETSc backend (mechanics/static_solver_petsc.hpp) in one process: the
// moduli and the sequential linear analysis equal those of the default backend to solver
// tolerance, a lattice gives its closed-form modulus, and a Krylov method chosen through the
// PETSc options converges to the same answer. Compiled only in a build with PETSc; the runs on
// two MPI ranks are the CLI test static_solver_petsc_cli (tests/mechanics/static_solver_petsc_cli.sh).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "../test_packings.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/generate/lattice.hpp"
#include "packlab/mechanics/opal_materials.hpp"
#include "packlab/mechanics/static_loading.hpp"
#include "packlab/mechanics/static_solver.hpp"
#include "silica_compression.hpp"

using namespace packlab;
using namespace packlab::mechanics;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double r = 7.5e-9;             // the opal paper's 15 nm particles
constexpr double E = 6.53e9, nu = 0.17;  // silica bonds

UniaxialCompressionOptions compression_options(const std::string& backend, double strength = inf) {
  UniaxialCompressionOptions o = test::silica_compression_options(E, nu, strength);
  o.solver = "static";
  o.solver_backend = backend;
  return o;
}

Packing random_bonded_sample(long n, unsigned seed) { return test::random_bonded_sample(n, seed, r); }

}  // namespace

TEST(StaticSolverPetsc, IsABackendOfThisBuild) {
  const std::vector<std::string> backends = static_solver_backends();
  EXPECT_NE(std::find(backends.begin(), backends.end(), "petsc"), backends.end());
  EXPECT_NE(backends.front(), "petsc");  // "auto" never picks it
}

// The closed form of StaticSolver.SimpleCubicColumnsOfBeamBondsGiveTheClosedFormModulus: elastic
// beam bonds along the axes of a simple cubic column give E = (pi / 4) E_b.
TEST(StaticSolverPetsc, SimpleCubicColumnsGiveTheClosedFormModulus) {
  UniaxialCompressionOptions o = compression_options("petsc");
  o.max_strain = 0.003;
  const UniaxialCompressionResult axial =
      run_uniaxial_compression(test::bonded_lattice(generate::LatticeType::sc, {3, 3, 8}, r, 1.01), o);
  EXPECT_NEAR(axial.youngs_modulus, std::numbers::pi / 4 * E, 1e-8 * E);
  EXPECT_EQ(axial.broken_bonds, 0u);
  EXPECT_GT(axial.factor_nonzeros, 0u);  // MUMPS's factor
}

TEST(StaticSolverPetsc, ModulusOfARandomSampleEqualsTheDefaultBackend) {
  const Packing p = random_bonded_sample(300, 3);
  UniaxialCompressionOptions o = compression_options("auto");
  o.max_strain = 0.003;
  o.sides = "open";
  const UniaxialCompressionResult reference = run_uniaxial_compression(p, o);
  o.solver_backend = "petsc";
  const UniaxialCompressionResult distributed = run_uniaxial_compression(p, o);
  ASSERT_GT(reference.youngs_modulus, 0.0);
  EXPECT_NEAR(distributed.youngs_modulus, reference.youngs_modulus, 1e-8 * reference.youngs_modulus);
  EXPECT_NEAR(distributed.poisson_ratio, reference.poisson_ratio, 1e-8);
}

// Sequential linear analysis: after each break the PETSc backend solves by conjugate gradients
// preconditioned with the last factor (refactorizing when that takes too long), the default
// backend downdates its factor; both to the solver tolerance, so the same bonds break in the
// same order at the same strains.
TEST(StaticSolverPetsc, SequentialLinearAnalysisEqualsTheDefaultBackend) {
  const Packing p = random_bonded_sample(300, 3);
  UniaxialCompressionOptions o = compression_options("auto", 94.3e6);  // silica (Table 1)
  for (auto& b : o.bond_materials) b.compressive_breakage = true;
  o.max_strain = 0.05;
  o.max_breaks = 60;
  const UniaxialCompressionResult reference = run_uniaxial_compression(p, o);
  o.solver_backend = "petsc";
  const UniaxialCompressionResult distributed = run_uniaxial_compression(p, o);
  ASSERT_GT(reference.broken_bonds, 10u);
  ASSERT_EQ(distributed.broken_bonds, reference.broken_bonds);
  for (std::size_t k = 0; k < reference.breaks.size(); ++k) {
    EXPECT_EQ(distributed.breaks[k].bond, reference.breaks[k].bond) << "break " << k;
    EXPECT_NEAR(distributed.break_strain[k], reference.break_strain[k], 1e-8 * reference.break_strain[k]);
  }
  EXPECT_NEAR(distributed.strength, reference.strength, 1e-8 * reference.strength);
  EXPECT_NEAR(distributed.youngs_modulus, reference.youngs_modulus, 1e-8 * reference.youngs_modulus);
}

// The options database is the user's: conjugate gradients with a Jacobi preconditioner instead
// of the factorization. The solver checks such a solve on the assembled matrix and refines it,
// so the modulus is the same to the solver tolerance.
TEST(StaticSolverPetsc, AKrylovMethodFromTheOptionsGivesTheSameModulus) {
  const Packing p = random_bonded_sample(300, 3);
  UniaxialCompressionOptions o = compression_options("auto");
  o.max_strain = 0.003;
  const UniaxialCompressionResult reference = run_uniaxial_compression(p, o);
  o.solver_backend = "petsc";
  o.petsc_options = "-ksp_type cg -pc_type jacobi -ksp_max_it 100000 -ksp_rtol 1e-13";
  const UniaxialCompressionResult iterative = run_uniaxial_compression(p, o);
  EXPECT_NEAR(iterative.youngs_modulus, reference.youngs_modulus, 1e-7 * reference.youngs_modulus);
  EXPECT_EQ(iterative.factor_nonzeros, 0u);  // no factor
}
