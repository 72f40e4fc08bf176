// Coordination: exact lattice values, rattlers (single pass and iterative, against
// PackingGeneration's own counts for the anchor packings), per type and between types,
// several packings accumulated.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "packlab/analyze/coordination.hpp"
#include "packlab/core/error.hpp"
#include "packlab/generate/lattice.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::analyze {
namespace {

Packing lattice(generate::LatticeType type, std::array<int, 3> cells, double gap = 0.0) {
  generate::LatticeParams p;
  p.type = type;
  p.cells = cells;
  p.radius = 0.25e-6;
  p.gap = gap * 2 * p.radius;
  return generate::make_lattice(p);
}

TEST(Coordination, LatticesHaveExactCountsAndNoRattlers) {
  struct Case {
    generate::LatticeType type;
    int z;
  };
  for (const Case c : {Case{generate::LatticeType::sc, 6}, Case{generate::LatticeType::bcc, 8},
                       Case{generate::LatticeType::fcc, 12}}) {
    const Packing packing = lattice(c.type, {3, 4, 5});
    Coordination cn(0.01);
    cn.compute(packing);
    for (int k : cn.counts()) ASSERT_EQ(k, c.z);
    EXPECT_EQ(cn.contacts(), packing.size() * c.z / 2);
    EXPECT_DOUBLE_EQ(cn.mean(), c.z);
    EXPECT_DOUBLE_EQ(cn.mean_without_rattlers(), c.z);
    EXPECT_EQ(cn.rattler_count(), 0u);
    ASSERT_EQ(cn.distribution().size(), static_cast<std::size_t>(c.z + 1));
    EXPECT_EQ(cn.distribution()[c.z], static_cast<long>(packing.size()));
  }
}

TEST(Coordination, SeparatedLatticeIsAllRattlers) {
  const Packing packing = lattice(generate::LatticeType::fcc, {3, 3, 3}, 0.02);  // gap 2 % of d
  Coordination cn(0.01);
  cn.compute(packing);
  EXPECT_EQ(cn.contacts(), 0u);
  EXPECT_EQ(cn.rattler_count(), packing.size());
  EXPECT_DOUBLE_EQ(cn.mean_without_rattlers(), 0.0);
  Coordination loose(0.03);
  loose.compute(packing);
  EXPECT_DOUBLE_EQ(loose.mean(), 12.0);
}

TEST(Coordination, IterativeRattlerRemovalCascades) {
  // Three touching spheres in a row, open box: ends have 1 contact, the middle 2. With a
  // threshold of 2 one pass flags the ends; removing them leaves the middle with none.
  Packing p;
  p.box.periodic = {false, false, false};
  p.box.length = {10, 10, 10};
  for (int k = 0; k < 3; ++k) p.add({2.0 + 2.0 * k, 5, 5}, 1.0);
  Coordination once(0.01, 2, RattlerRule::single_pass), repeated(0.01, 2, RattlerRule::iterative);
  once.compute(p);
  repeated.compute(p);
  EXPECT_EQ(once.counts(), (std::vector<int>{1, 2, 1}));
  EXPECT_EQ(once.rattlers(), (std::vector<std::uint8_t>{1, 0, 1}));
  EXPECT_EQ(repeated.rattlers(), (std::vector<std::uint8_t>{1, 1, 1}));
  EXPECT_DOUBLE_EQ(once.mean_without_rattlers(), 0.0);  // the middle's partners are rattlers
  EXPECT_DOUBLE_EQ(once.mean(), 4.0 / 3.0);
}

TEST(Coordination, AnchorPackingsMatchPackingGenerationsRattlerCounts) {
  // tests/data/anchor-packings.tar.xz, README.md: at strain 1e-7, pg-ls-mono-10k has 9,561
  // non-rattlers with 5.61 mean contacts, pg-ls-bi-10k 6,460 with 5.64 (PackingGeneration's
  // own analysis). Its rattlers have fewer than 3 contacts, removed iteratively.
  const std::filesystem::path dir = PACKLAB_ANCHOR_PACKINGS;
  struct Case {
    const char* file;
    std::size_t non_rattlers;
    double mean;
  };
  for (const Case c : {Case{"pg-ls-mono-10k.txt", 9561, 5.61}, Case{"pg-ls-bi-10k.txt", 6460, 5.64}}) {
    const Packing packing = io::read_packing(dir / c.file);
    Coordination cn(1e-7, 3, RattlerRule::iterative);
    cn.compute(packing);
    EXPECT_EQ(packing.size() - cn.rattler_count(), c.non_rattlers) << c.file;
    EXPECT_NEAR(cn.mean_without_rattlers(), c.mean, 0.005) << c.file;  // README gives 2 decimals
  }
}

TEST(Coordination, PerTypeAndBetweenTypesOnFccSublattices) {
  // FCC: a corner-site particle has its 12 neighbours on the three face-centre sublattices;
  // a face-centre particle has 4 corner-site and 8 face-centre neighbours.
  Packing packing = lattice(generate::LatticeType::fcc, {3, 3, 3});
  const double a = generate::lattice_constant({generate::LatticeType::fcc, {3, 3, 3}, 0.25e-6, 0.0});
  long corners = 0;
  for (std::size_t i = 0; i < packing.size(); ++i) {
    bool corner = true;
    for (int ax = 0; ax < 3; ++ax) {
      const double f = (packing.position[i][ax] - 0.25 * a) / a;
      corner = corner && std::abs(f - std::round(f)) < 1e-6;
    }
    packing.type[i] = corner ? 7 : 2;
    corners += corner;
  }
  Coordination cn(0.01);
  cn.compute(packing);
  ASSERT_EQ(cn.types(), (std::vector<int>{2, 7}));
  EXPECT_EQ(cn.particles_by_type()[1], corners);
  EXPECT_EQ(cn.particles_by_type()[0], static_cast<long>(packing.size()) - corners);
  const auto z = cn.between_types();
  EXPECT_DOUBLE_EQ(z[1][0], 12.0);  // corner with face
  EXPECT_DOUBLE_EQ(z[1][1], 0.0);
  EXPECT_DOUBLE_EQ(z[0][1], 4.0);
  EXPECT_DOUBLE_EQ(z[0][0], 8.0);
  EXPECT_EQ(cn.mean_by_type(), (std::vector<double>{12.0, 12.0}));
}

TEST(Coordination, SeveralPackingsAccumulate) {
  const Packing sc = lattice(generate::LatticeType::sc, {3, 3, 3});    // 27 particles, z = 6
  const Packing bcc = lattice(generate::LatticeType::bcc, {3, 3, 3});  // 54 particles, z = 8
  Coordination cn(0.01);
  cn.compute(sc);
  cn.compute(bcc, /*reset=*/false);
  EXPECT_EQ(cn.frames(), 2);
  EXPECT_EQ(cn.particle_count(), 81u);
  EXPECT_DOUBLE_EQ(cn.mean(), (27.0 * 6 + 54.0 * 8) / 81.0);
  EXPECT_EQ(cn.distribution()[6], 27);
  EXPECT_EQ(cn.distribution()[8], 54);
  EXPECT_EQ(cn.counts().size(), 54u);  // per-particle arrays: the last packing
  cn.compute(sc);                      // reset
  EXPECT_EQ(cn.frames(), 1);
  EXPECT_DOUBLE_EQ(cn.mean(), 6.0);
}

TEST(Coordination, ReadingBeforeComputingIsALogicError) {
  Coordination cn(0.01);
  EXPECT_THROW((void)cn.counts(), std::logic_error);
  EXPECT_THROW((void)cn.mean_without_rattlers(), std::logic_error);
  EXPECT_THROW((void)cn.distribution(), std::logic_error);
  EXPECT_THROW(Coordination(-0.1), InputError);
  EXPECT_THROW(Coordination(0.01, -1), InputError);
  EXPECT_THROW((void)rattler_rule_from_name("sometimes"), InputError);
}

}  // namespace
}  // namespace packlab::analyze
