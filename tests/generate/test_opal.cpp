#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "../input_error.hpp"
#include "packlab/core/error.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/generate/opal.hpp"

using namespace packlab;
using namespace packlab::generate;

namespace {

constexpr double pi = std::numbers::pi;

// Simple-cubic particle lattice of diameter 1, centres at (i + 1/2, j + 1/2, k + 1/2), box
// periodic along x and y, open along z.
Packing sc_lattice(int nx, int ny, int nz) {
  Packing p;
  p.box.lo = {0, 0, 0};
  p.box.length = {double(nx), double(ny), double(nz)};
  p.box.periodic = {true, true, false};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) p.add({i + 0.5, j + 0.5, k + 0.5}, 0.5);
  return p;
}

// Pore lattice [100] with a cubic period of exactly `period` (spacing 1: touching pores).
FccPores fcc100(double period) {
  FccPores f;
  f.diameter = period / std::sqrt(2.0);
  f.orientation = FccOrientation::z100;
  return f;
}

// [100] pores of period 14 (diameter 9.9 d) in a titania coating 0.8 d thick.
OpalOptions coated_fcc100() {
  OpalOptions o;
  o.fcc = fcc100(14.0);
  o.coating_thickness = 0.8;
  return o;
}

// Distances of x to every pore (minimum image), brute force.
std::vector<double> pore_distances(const Box& box, const PoreSet& pores, const Vec3& x) {
  std::vector<double> L;
  for (const Vec3& c : pores.centre) L.push_back(norm(box.minimum_image(c - x)));
  return L;
}

// Exact input index of each model particle (positions are copied unchanged).
std::vector<long> input_index(const Packing& in, const Packing& out) {
  std::vector<long> idx;
  std::size_t k = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    while (k < in.size() && !(in.position[k] == out.position[i])) ++k;
    idx.push_back(static_cast<long>(k));
    ++k;
  }
  return idx;
}

// Volume fraction of the union of spheres of radius R + grow around the pores inside
// [lo, hi] along z, by a fine grid (independent of the particles).
double union_fraction(const Box& box, const PoreSet& pores, double grow, double zlo, double zhi, double h) {
  long inside = 0, total = 0;
  for (double z = zlo + h / 2; z < zhi; z += h)
    for (double y = box.lo.y + h / 2; y < box.hi().y; y += h)
      for (double x = box.lo.x + h / 2; x < box.hi().x; x += h) {
        ++total;
        const auto L = pore_distances(box, pores, {x, y, z});
        for (std::size_t k = 0; k < L.size(); ++k)
          if (L[k] <= pores.radius[k] + grow) {
            ++inside;
            break;
          }
      }
  return double(inside) / double(total);
}

int expected_material(int ti, int tj) {
  const bool ti_ti = ti == particle_type::coating, tj_ti = tj == particle_type::coating;
  if (ti_ti || tj_ti) return opal_bond_material::titania;
  if (ti == particle_type::substrate && tj == particle_type::substrate) return opal_bond_material::substrate;
  return opal_bond_material::silica;
}

using test::error_of;

}  // namespace

TEST(OpalPores, FccLatticeHasThePackingFractionOfTouchingSpheres) {
  for (auto o : {FccOrientation::z100, FccOrientation::z111}) {
    FccPores f;
    f.diameter = 2.0;
    f.orientation = o;
    f.auto_origin = false;
    f.origin = {0.1, 0.2, 0.3};
    const Vec3 per = fcc_pore_period(f);
    Box box;
    box.length = {2 * per.x, per.y, 2 * per.z};
    const PoreSet pores = fcc_pores(box, f, 0.0);
    const long cell_points = o == FccOrientation::z100 ? 4 : 6;
    ASSERT_EQ(long(pores.size()), 4 * cell_points) << fcc_orientation_name(o);
    double vol = 0, dmin = 1e9;
    for (std::size_t a = 0; a < pores.size(); ++a) {
      vol += 4.0 / 3.0 * pi * std::pow(pores.radius[a], 3);
      for (std::size_t b = a + 1; b < pores.size(); ++b)
        dmin = std::min(dmin, norm(box.minimum_image(pores.centre[b] - pores.centre[a])));
    }
    EXPECT_NEAR(vol / box.volume(), pi / (3 * std::sqrt(2.0)), 1e-12);  // 0.7405
    EXPECT_NEAR(dmin, 2.0, 1e-12);                                      // touching
  }
}

TEST(Opal, UncoatedFccPoresOnALatticeRemoveExactlyEq1) {
  const double period = 14.0;  // pore diameter 9.9 d: ratio ~10
  const Packing in = sc_lattice(14, 14, 30);
  OpalOptions o;
  o.fcc = fcc100(period);
  OpalSummary s;
  const Packing out = build_opal(in, o, &s);
  const PoreSet pores = opal_pores(in, o);
  EXPECT_TRUE(s.lattice_commensurate);
  EXPECT_EQ(s.pores, long(pores.size()));
  // Removed = exactly the particles satisfying eq. (1) for some pore.
  long in_pore = 0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const auto L = pore_distances(in.box, pores, in.position[i]);
    bool inside = false;
    for (std::size_t k = 0; k < L.size(); ++k) inside = inside || L[k] <= pores.radius[k] + in.radius[i];
    in_pore += inside;
  }
  EXPECT_EQ(s.removed, in_pore);
  EXPECT_EQ(long(out.size()), long(in.size()) - in_pore);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto L = pore_distances(out.box, pores, out.position[i]);
    for (std::size_t k = 0; k < L.size(); ++k) ASSERT_GT(L[k], pores.radius[k] + out.radius[i]);
  }
  // Substrate: the two bottom layers (z < 2 d), fixed; nothing else fixed; no pore cuts them.
  EXPECT_EQ(s.substrate, 2 * 14 * 14);
  EXPECT_NEAR(s.substrate_top, 2.0, 1e-12);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const bool sub = out.position[i].z < 2.0;
    EXPECT_EQ(out.type[i], sub ? particle_type::substrate : particle_type::structural);
    EXPECT_EQ(out.fixed[i], sub ? 1 : 0);
  }
  EXPECT_EQ(s.coating, 0);
  // Porosity of the sample (above the substrate, two whole lattice periods) against the
  // geometric union of pores grown by a particle radius (eq. 1), from a fine grid.
  const double geometric = union_fraction(in.box, pores, 0.5, 2.0, 30.0, 0.25);
  EXPECT_NEAR(s.porosity, geometric, 0.015) << geometric;
  EXPECT_GT(s.porosity, pi / (3 * std::sqrt(2.0)));  // eq. 1 grows the pores by r
  EXPECT_NEAR(s.density, 1297.0 * (1.0 - s.porosity), 1e-9);
  EXPECT_NEAR(s.particle_porosity, 1.0 - double(out.size()) * pi / 6.0 / in.box.volume(), 1e-12);
}

TEST(Opal, BondsFollowTheCutoffAcrossPeriodicBoundariesWithMaterials) {
  const Packing in = sc_lattice(14, 14, 20);
  const OpalOptions o = coated_fcc100();
  OpalSummary s;
  const Packing out = build_opal(in, o, &s);
  ASSERT_GT(s.coating, 0);
  // Brute force: every pair (and periodic image) closer than 1.75 d is bonded, once.
  long pairs = 0;
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::size_t j = i + 1; j < out.size(); ++j) {
      const Vec3 d = out.box.minimum_image(out.position[j] - out.position[i]);
      pairs += norm(d) < 1.75 * (out.radius[i] + out.radius[j]);
    }
  EXPECT_EQ(s.bonds, pairs);
  EXPECT_EQ(long(out.bonds.size()), pairs);
  EXPECT_NEAR(s.mean_coordination, 2.0 * double(pairs) / double(out.size()), 1e-12);
  std::array<long, 3> by{0, 0, 0};
  long periodic = 0;
  for (std::size_t b = 0; b < out.bonds.size(); ++b) {
    const int i = out.bonds.i[b], j = out.bonds.j[b];
    const auto& img = out.bonds.image[b];
    const Vec3 d = out.position[std::size_t(j)] + out.box.shift_vector(img) - out.position[std::size_t(i)];
    ASSERT_NEAR(out.bonds.rest_length[b], norm(d), 1e-12);  // rest length = image distance
    ASSERT_LT(norm(d), 1.75);
    EXPECT_EQ(img[2], 0);  // z is open
    periodic += img[0] != 0 || img[1] != 0;
    ASSERT_EQ(out.bonds.material[b], expected_material(out.type[std::size_t(i)], out.type[std::size_t(j)]));
    ++by[std::size_t(out.bonds.material[b])];
  }
  EXPECT_GT(periodic, 0);
  EXPECT_EQ(periodic, s.periodic_bonds);
  for (int m = 0; m < 3; ++m) {
    EXPECT_GT(by[std::size_t(m)], 0);
    EXPECT_EQ(by[std::size_t(m)], s.bonds_by_material[std::size_t(m)]);
  }
  EXPECT_EQ(opal_bond_material_of(particle_type::structural, particle_type::substrate), opal_bond_material::silica);
  EXPECT_EQ(opal_bond_material_of(particle_type::coating, particle_type::substrate), opal_bond_material::titania);
  EXPECT_EQ(opal_bond_material_of(particle_type::structural, particle_type::coating), opal_bond_material::titania);
  EXPECT_EQ(opal_bond_material_of(particle_type::pore, particle_type::structural), -1);
}

TEST(Opal, CoatingIsTheShellOfEq2KeepingOpeningsFree) {
  const Packing in = sc_lattice(14, 14, 30);
  const OpalOptions o = coated_fcc100();
  OpalSummary s;
  const Packing out = build_opal(in, o, &s);
  const PoreSet pores = opal_pores(in, o);
  // Brute-force classification of every input particle.
  const double Lc = o.coating_thickness;
  std::vector<int> cls(in.size(), 0);  // 0 silica, 1 candidate, 2 removed
  for (std::size_t i = 0; i < in.size(); ++i) {
    const auto L = pore_distances(in.box, pores, in.position[i]);
    bool inside = false, deep = false;
    for (std::size_t k = 0; k < L.size(); ++k) {
      const double reach = pores.radius[k] + in.radius[i];
      if (L[k] <= reach) inside = true;
      if (L[k] < reach - Lc) deep = true;  // not within L_coat of this pore's surface (eq. 2)
    }
    cls[i] = !inside ? 0 : (deep ? 2 : 1);
  }
  long openings = 0;
  std::vector<int> expected_type(in.size(), -1);
  for (std::size_t i = 0; i < in.size(); ++i) {
    if (cls[i] == 0) expected_type[i] = particle_type::structural;
    if (cls[i] != 1) continue;
    bool near = false;
    for (std::size_t k = 0; k < in.size() && !near; ++k)
      near = cls[k] == 0 &&
             norm(in.box.minimum_image(in.position[k] - in.position[i])) - in.radius[k] <= Lc + in.radius[i];
    if (near)
      expected_type[i] = particle_type::coating;
    else
      ++openings;
  }
  for (std::size_t i = 0; i < in.size(); ++i)
    if (expected_type[i] >= 0 && in.position[i].z < 2.0) expected_type[i] = particle_type::substrate;
  EXPECT_EQ(s.coating_openings, openings);
  EXPECT_GT(openings, 0);
  const auto idx = input_index(in, out);
  long kept = 0;
  for (std::size_t i = 0; i < in.size(); ++i) kept += expected_type[i] >= 0;
  ASSERT_EQ(long(out.size()), kept);
  for (std::size_t m = 0; m < out.size(); ++m) ASSERT_EQ(out.type[m], expected_type[std::size_t(idx[m])]) << m;
  // Openings: the contact point of two touching pores stays free of particles.
  for (std::size_t a = 0; a < pores.size(); ++a)
    for (std::size_t b = a + 1; b < pores.size(); ++b) {
      const Vec3 d = in.box.minimum_image(pores.centre[b] - pores.centre[a]);
      if (std::abs(norm(d) - 2 * pores.radius[a]) > 1e-9) continue;
      const Vec3 mid = pores.centre[a] + d * 0.5;
      if (mid.z < 2.0 || mid.z > 30.0) continue;
      for (const Vec3& x : out.position) ASSERT_GT(norm(in.box.minimum_image(x - mid)), 0.7);
    }
  // Without the openings filter (very large opening distance) the openings close.
  OpalOptions closed = o;
  closed.opening_distance_ratio = 10.0;
  OpalSummary s2;
  build_opal(in, closed, &s2);
  EXPECT_EQ(s2.coating_openings, 0);
  EXPECT_EQ(s2.coating, s.coating + openings);
  EXPECT_NEAR(
      s.density,
      (1297.0 * double(s.structural) + 3660.0 * double(s.coating)) /
          double(std::count_if(in.position.begin(), in.position.end(), [](const Vec3& x) { return x.z >= 2.0; })),
      1e-9);
}

TEST(Opal, FbaPackingWith111PoresHasNoCentreInAPore) {
  // Pore diameter 8 d, [111] along z, one lattice period along y and z, two along x.
  FccPores f;
  f.diameter = 8.0;
  const Vec3 per = fcc_pore_period(f);
  Box box;
  box.length = {2 * per.x, per.y, per.z + 2.0};
  box.periodic = {true, true, false};
  SizeClasses mono;
  Random rng(5);
  const long n = fba_count_for_volume(box.volume(), 0.40, 1.0, mono);
  FbaParams fp;
  fp.target_porosity = 0.40;
  const FbaResult fba = fba_pack(box, fba_class_radii(n, mono, rng), fp, rng);
  ASSERT_EQ(fba.status.stop, FbaStop::target_reached);
  OpalOptions o;
  o.fcc = f;
  OpalSummary s;
  const Packing out = build_opal(fba.packing, o, &s);
  const PoreSet pores = opal_pores(fba.packing, o);
  EXPECT_TRUE(s.lattice_commensurate);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto L = pore_distances(out.box, pores, out.position[i]);
    for (std::size_t k = 0; k < L.size(); ++k) ASSERT_GT(L[k], pores.radius[k] + out.radius[i]);
    EXPECT_EQ(out.fixed[i], out.position[i].z < s.substrate_top ? 1 : 0);
  }
  const double r = fba.packing.radius[0];
  const double geometric = union_fraction(box, pores, r, s.substrate_top, s.substrate_top + per.z, 0.3);
  EXPECT_NEAR(s.porosity, geometric, 0.03) << geometric;
  EXPECT_NEAR(s.mean_coordination, 2.0 * double(out.bonds.size()) / double(out.size()), 1e-12);
  EXPECT_GT(s.mean_coordination, 4.0);
}

TEST(Opal, RandomPoresFromTheForceBiasedAlgorithm) {
  Packing in = sc_lattice(24, 24, 26);
  const Box region = random_pore_region(in, 2.0);  // above the substrate slab and r_max
  EXPECT_NEAR(region.lo.z, 2.5, 1e-12);
  EXPECT_NEAR(region.length.z, 23.5, 1e-12);
  RandomPores rp;
  rp.diameter = 8.0;
  rp.count = 20;  // pore fraction 20 x 268 / 13536 = 0.40
  Random rng(4);
  OpalOptions o;
  o.pores = random_pores(region, rp, rng);
  OpalSummary s;
  const Packing out = build_opal(in, o, &s);
  EXPECT_EQ(s.pores, 20);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto L = pore_distances(out.box, o.pores, out.position[i]);
    for (std::size_t k = 0; k < L.size(); ++k) ASSERT_GT(L[k], 4.0 + 0.5);
  }
  const double geometric = union_fraction(in.box, o.pores, 0.5, 2.0, 26.0, 0.4);
  EXPECT_NEAR(s.porosity, geometric, 0.02);
  EXPECT_EQ(s.substrate, 2 * 24 * 24);  // pores stay above the substrate region
}

// Periodic random pores over the whole box (pore_boundary = periodic): they cut the top and
// the bottom face and reach into the substrate slab, as the paper's pores reach its fixed layer;
// the particles removed are those of eq. 1 for some pore or image, and the porosity is the pore
// volume fraction of the box.
TEST(Opal, PeriodicRandomPoresCutTheFacesAndTheSubstrate) {
  Packing in = sc_lattice(24, 24, 26);
  RandomPores rp;
  rp.diameter = 8.0;
  rp.count = 26;  // pore fraction 26 x 268.1 / 14976 = 0.465
  rp.periodic = true;
  Random rng(4);
  OpalOptions o;
  o.pores = random_pores(in.box, rp, rng);
  ASSERT_GT(o.pores.size(), 26u);  // images at the opposite faces
  OpalSummary s;
  const Packing out = build_opal(in, o, &s);
  long in_pore = 0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const auto L = pore_distances(in.box, o.pores, in.position[i]);
    bool inside = false;
    for (std::size_t k = 0; k < L.size(); ++k) inside = inside || L[k] <= 4.0 + in.radius[i];
    in_pore += inside;
  }
  EXPECT_EQ(s.removed, in_pore);
  EXPECT_LT(s.substrate, 2 * 24 * 24);  // the substrate slab is cut too
  // The box loses the pore volume fraction exactly (grid of 20 cells per pore diameter) ...
  EXPECT_NEAR(union_fraction(in.box, o.pores, 0.0, 0.0, 26.0, 0.4), 26.0 * std::numbers::pi / 6.0 * 512.0 / 14976.0,
              0.005);
  // ... and the particles above the substrate those whose centres lie within R + r of a pore.
  EXPECT_NEAR(s.porosity, union_fraction(in.box, o.pores, 0.5, 2.0, 26.0, 0.4), 0.02);
}

// Random pores packed at a spacing: D = 8 cut spheres packed as spheres of 1.25 x 8 = 10, so no
// two centres are closer than 10 (the interpore walls are at least 2 thick), and the fraction
// counted is that of the packed spheres.
TEST(Opal, RandomPoresAtASpacingKeepTheirCentresThatFarApart) {
  RandomPores rp;
  rp.diameter = 8.0;
  rp.count = 14;  // packed fraction 14 x 523.6 / 14976 = 0.49
  rp.periodic = true;
  rp.spacing_ratio = 1.25;
  Random rng(7);
  const Packing in = sc_lattice(24, 24, 26);
  const PoreSet pores = random_pores(in.box, rp, rng);
  Box all_periodic = in.box;
  all_periodic.periodic = {true, true, true};
  for (std::size_t i = 0; i < 14; ++i) {
    EXPECT_EQ(pores.radius[i], 4.0);
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_GE(norm(all_periodic.minimum_image(pores.centre[i] - pores.centre[j])), 10.0 * (1.0 - 1e-3));
  }
  rp.count = 21;  // packed fraction 0.73
  EXPECT_NE(error_of([&] { random_pores(in.box, rp, rng); }).find("< 0.7"), std::string::npos);
  rp.spacing_ratio = 0.4;
  EXPECT_NE(error_of([&] { random_pores(in.box, rp, rng); }).find("pore_spacing = 0.4"), std::string::npos);
}

TEST(Opal, BadInputNamesKeyValueAndRange) {
  const Packing in = sc_lattice(14, 14, 10);
  OpalOptions o;
  EXPECT_NE(error_of([&] { build_opal(in, o); }).find("pores"), std::string::npos);
  o.fcc = fcc100(14.0);
  o.bond_cutoff_ratio = 2.5;
  const std::string m = error_of([&] { build_opal(in, o); });
  EXPECT_NE(m.find("bond_cutoff = 2.5"), std::string::npos) << m;
  EXPECT_NE(m.find("[1, 2)"), std::string::npos) << m;
  o.bond_cutoff_ratio = 1.75;
  o.coating_thickness = -1;
  EXPECT_NE(error_of([&] { build_opal(in, o); }).find("coating = -1"), std::string::npos);
  o.coating_thickness = 0;
  o.fcc.spacing_ratio = 0.1;
  EXPECT_NE(error_of([&] { build_opal(in, o); }).find("pore_spacing = 0.1"), std::string::npos);
  o.fcc.spacing_ratio = 1;
  o.fcc.diameter = 30;  // a pore larger than the periodic box
  EXPECT_NE(error_of([&] { build_opal(in, o); }).find("box length x"), std::string::npos);
  o.fcc = fcc100(14.0);
  o.pores.centre.push_back({1, 1, 1});
  o.pores.radius.push_back(1);
  EXPECT_NE(error_of([&] { build_opal(in, o); }).find("not both"), std::string::npos);
  EXPECT_NE(error_of([] { fcc_orientation_from_name("110"); }).find("orientation = 110"), std::string::npos);
}
