// Fabric tensor: cubic lattices are isotropic (trace 1, deviator 0), a chain is uniaxial,
// the contact-normal densities of SC are exact, a dense random packing is nearly isotropic.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "packlab/analyze/fabric.hpp"
#include "packlab/generate/lattice.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::analyze {
namespace {

TEST(Fabric, CubicLatticesAreIsotropic) {
  for (auto type : {generate::LatticeType::sc, generate::LatticeType::bcc, generate::LatticeType::fcc}) {
    generate::LatticeParams p;
    p.type = type;
    p.cells = {3, 3, 4};
    const Packing packing = generate::make_lattice(p);
    Fabric fabric(0.01);
    fabric.compute(packing);
    const auto& t = fabric.tensor();
    EXPECT_NEAR(t[0][0] + t[1][1] + t[2][2], 1.0, 1e-14);
    for (const auto& row : fabric.deviator())
      for (double v : row) EXPECT_NEAR(v, 0.0, 1e-14);
    for (double e : fabric.eigenvalues()) EXPECT_NEAR(e, 1.0 / 3.0, 1e-14);
    EXPECT_NEAR(fabric.anisotropy(), 0.0, 1e-12);
  }
}

TEST(Fabric, SimpleCubicNormalDensityIsExact) {
  generate::LatticeParams p;
  p.type = generate::LatticeType::sc;
  p.cells = {3, 3, 3};
  Fabric fabric(0.01, 10);
  fabric.compute(generate::make_lattice(p));
  EXPECT_EQ(fabric.contacts(), 27 * 3);
  // A third of the normals lie along each axis: |n.e| = 1 (last bin) or 0 (first bin).
  for (int a = 0; a < 3; ++a) {
    EXPECT_DOUBLE_EQ(fabric.normal_density()[0][a], 10.0 * 2.0 / 3.0);
    EXPECT_DOUBLE_EQ(fabric.normal_density()[9][a], 10.0 / 3.0);
    for (int k = 1; k < 9; ++k) EXPECT_EQ(fabric.normal_density()[k][a], 0.0);
  }
}

TEST(Fabric, ChainIsUniaxial) {
  // Spheres touching along x only (y and z edges far beyond contact range).
  Packing chain;
  chain.box.length = {10.0, 50.0, 50.0};
  for (int k = 0; k < 5; ++k) chain.add({1.0 + 2.0 * k, 25, 25}, 1.0);
  Fabric fabric(0.01);
  fabric.compute(chain);
  EXPECT_EQ(fabric.contacts(), 5);  // periodic along x: the last touches the first
  EXPECT_NEAR(fabric.tensor()[0][0], 1.0, 1e-15);
  EXPECT_NEAR(fabric.tensor()[1][1], 0.0, 1e-15);
  EXPECT_NEAR(fabric.eigenvalues()[0], 1.0, 1e-15);
  EXPECT_NEAR(fabric.anisotropy(), 7.5, 1e-12);  // sqrt(3/2 a:a), a = 15/2 diag(2/3, -1/3, -1/3)
}

TEST(Fabric, DenseRandomPackingIsNearlyIsotropic) {
  // Isotropic normals give E[a^2] = 56.25 / N_c (a_rms = 7.5/sqrt(N_c)); allow 3 a_rms.
  const std::filesystem::path file = std::filesystem::path(PACKLAB_ANCHOR_PACKINGS) / "pg-ls-mono-10k.txt";
  Fabric fabric(1e-7);
  fabric.compute(io::read_packing(file));
  ASSERT_GT(fabric.contacts(), 20000);
  EXPECT_LT(fabric.anisotropy(), 3 * 7.5 / std::sqrt(static_cast<double>(fabric.contacts())));
  // Each bin's density has a binomial sd of about sqrt(bins / N_c): allow 4 of them.
  const double sd = std::sqrt(fabric.bins() / static_cast<double>(fabric.contacts()));
  for (int k = 0; k < fabric.bins(); ++k)
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(fabric.normal_density()[k][a], 1.0, 4 * sd);
}

TEST(Fabric, ReadingBeforeComputingIsALogicError) {
  Fabric fabric;
  EXPECT_THROW((void)fabric.tensor(), std::logic_error);
  EXPECT_THROW((void)fabric.anisotropy(), std::logic_error);
}

}  // namespace
}  // namespace packlab::analyze
