#include "packlab/generate/opal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <set>

#include "packlab/core/error.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/io/options.hpp"

namespace packlab::generate {

namespace {

constexpr double pi = std::numbers::pi;
double sphere_volume(double r) { return 4.0 / 3.0 * pi * r * r * r; }

// Uniform cell grid of points for "all points within reach of x" queries, minimum image along
// periodic axes (each point visited at most once, also when the grid has < 3 cells per axis).
class CellGrid {
 public:
  CellGrid(const Box& box, const std::vector<Vec3>& points, double edge) : box_(box), points_(points) {
    // At most about 8 cells per point (and 256 per axis) whatever the edge.
    const int cap = std::clamp(static_cast<int>(std::cbrt(8.0 * static_cast<double>(points.size()) + 64.0)), 4, 256);
    for (int a = 0; a < 3; ++a) {
      n_[a] = std::clamp(static_cast<int>(box.length[a] / edge), 1, cap);
      h_[a] = box.length[a] / n_[a];
    }
    start_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
    std::vector<int> cell(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      cell[i] = index(coord(points[i]));
      ++start_[static_cast<std::size_t>(cell[i]) + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    items_.resize(points.size());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < points.size(); ++i)
      items_[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell[i])]++)] = static_cast<int>(i);
  }

  // Calls f(j, d) for every point j with |d| <= reach, d = minimum image of (point_j - x).
  template <class F>
  void query(const Vec3& x, double reach, F&& f) const {
    const std::array<int, 3> c = coord(box_.wrap(x));
    std::array<std::vector<int>, 3> range;
    for (int a = 0; a < 3; ++a) {
      const int span = static_cast<int>(std::ceil(reach / h_[a]));
      if (box_.periodic[a] && 2 * span + 1 >= n_[a]) {
        for (int k = 0; k < n_[a]; ++k) range[a].push_back(k);
      } else {
        for (int k = c[a] - span; k <= c[a] + span; ++k) {
          int kk = k;
          if (box_.periodic[a])
            kk = (k % n_[a] + n_[a]) % n_[a];
          else if (k < 0 || k >= n_[a])
            continue;
          range[a].push_back(kk);
        }
      }
    }
    const double reach2 = reach * reach;
    for (int kz : range[2])
      for (int ky : range[1])
        for (int kx : range[0]) {
          const std::size_t cell = static_cast<std::size_t>(kx + n_[0] * (ky + n_[1] * kz));
          for (int s = start_[cell]; s < start_[cell + 1]; ++s) {
            const int j = items_[static_cast<std::size_t>(s)];
            const Vec3 d = box_.minimum_image(points_[static_cast<std::size_t>(j)] - x);
            if (norm2(d) <= reach2) f(j, d);
          }
        }
  }

 private:
  std::array<int, 3> coord(const Vec3& p) const {
    std::array<int, 3> c{};
    for (int a = 0; a < 3; ++a)
      c[a] = std::clamp(static_cast<int>(std::floor((p[a] - box_.lo[a]) / h_[a])), 0, n_[a] - 1);
    return c;
  }
  int index(const std::array<int, 3>& c) const { return c[0] + n_[0] * (c[1] + n_[1] * c[2]); }

  Box box_;
  const std::vector<Vec3>& points_;
  std::array<int, 3> n_{1, 1, 1};
  std::array<double, 3> h_{1, 1, 1};
  std::vector<int> start_, items_;
};

bool is_solid(int t) {
  return t == particle_type::structural || t == particle_type::coating || t == particle_type::substrate;
}

}  // namespace

int opal_bond_material_of(int ti, int tj) {
  if (!is_solid(ti) || !is_solid(tj)) return -1;
  if (ti == particle_type::coating || tj == particle_type::coating) return opal_bond_material::titania;
  if (ti == particle_type::substrate && tj == particle_type::substrate) return opal_bond_material::substrate;
  return opal_bond_material::silica;  // silica–silica, silica–substrate
}

std::string fcc_orientation_name(FccOrientation o) { return o == FccOrientation::z111 ? "111" : "100"; }

FccOrientation fcc_orientation_from_name(const std::string& name) {
  if (name == "111" || name == "[111]") return FccOrientation::z111;
  if (name == "100" || name == "[100]") return FccOrientation::z100;
  fail_input("orientation = " + name + ": must be one of 111, 100 (the FCC direction along z)");
}

Vec3 fcc_pore_period(const FccPores& fcc) {
  const double a = fcc.spacing_ratio * fcc.diameter;
  if (fcc.orientation == FccOrientation::z111) return {a, a * std::sqrt(3.0), a * std::sqrt(6.0)};
  const double c = a * std::sqrt(2.0);
  return {c, c, c};
}

namespace {

// Lattice basis (in units of the nearest-neighbour distance a) of one repeat cell.
std::vector<Vec3> fcc_basis(FccOrientation o) {
  if (o == FccOrientation::z100) {
    const double c = std::sqrt(2.0);
    return {{0, 0, 0}, {c / 2, c / 2, 0}, {c / 2, 0, c / 2}, {0, c / 2, c / 2}};
  }
  const double s3 = std::sqrt(3.0), h = std::sqrt(2.0 / 3.0);
  // Close-packed layers A, B, C stacked along z (ABC = [111]).
  return {{0, 0, 0},          {0.5, s3 / 2, 0},   {0.5, s3 / 6, h},
          {0, 2 * s3 / 3, h}, {0, s3 / 3, 2 * h}, {0.5, 5 * s3 / 6, 2 * h}};
}

bool commensurate(const Box& box, const Vec3& period) {
  for (int a = 0; a < 3; ++a) {
    if (!box.periodic[a]) continue;
    const double k = box.length[a] / period[a];
    if (std::abs(k - std::round(k)) > 1e-4 * std::max(1.0, k) || std::round(k) < 1.0)
      return false;  // seam < 1e-4 period
  }
  return true;
}

struct Substrate {
  double bottom = 0, top = 0, mean_diameter = 0;
};

Substrate substrate_slab(const Packing& p, double layers) {
  Substrate s;
  if (p.size() == 0) return s;
  s.bottom = std::numeric_limits<double>::infinity();
  double sum = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    s.bottom = std::min(s.bottom, p.position[i].z - p.radius[i]);
    sum += 2.0 * p.radius[i];
  }
  s.mean_diameter = sum / static_cast<double>(p.size());
  s.top = s.bottom + layers * s.mean_diameter;
  return s;
}

}  // namespace

PoreSet fcc_pores(const Box& box, const FccPores& fcc, double pore_floor) {
  require(fcc.diameter > 0.0 && std::isfinite(fcc.diameter), "pore_diameter", fcc.diameter, "> 0 m");
  require(fcc.spacing_ratio >= 0.5 && fcc.spacing_ratio <= 2.0, "pore_spacing", fcc.spacing_ratio,
          "in [0.5, 2] (nearest-neighbour distance / pore diameter)");
  const double a = fcc.spacing_ratio * fcc.diameter, R = 0.5 * fcc.diameter;
  const Vec3 period = fcc_pore_period(fcc);
  const Vec3 origin = fcc.auto_origin ? Vec3{box.lo.x, box.lo.y, pore_floor + R} : fcc.origin;
  const std::vector<Vec3> basis = fcc_basis(fcc.orientation);
  std::array<long, 3> lo{}, hi{};
  for (int k = 0; k < 3; ++k) {
    lo[k] = static_cast<long>(std::floor((box.lo[k] - R - origin[k]) / period[k])) - 1;
    hi[k] = static_cast<long>(std::ceil((box.hi()[k] + R - origin[k]) / period[k])) + 1;
    require(hi[k] - lo[k] < 100000, "pore_diameter", fcc.diameter, "not tiny against the box (too many pores)");
  }
  PoreSet pores;
  for (long iz = lo[2]; iz <= hi[2]; ++iz)
    for (long iy = lo[1]; iy <= hi[1]; ++iy)
      for (long ix = lo[0]; ix <= hi[0]; ++ix)
        for (const Vec3& b : basis) {
          const Vec3 p{origin.x + (static_cast<double>(ix) * period.x + b.x * a),
                       origin.y + (static_cast<double>(iy) * period.y + b.y * a),
                       origin.z + (static_cast<double>(iz) * period.z + b.z * a)};
          // The automatic origin is the lowest pore layer (above the substrate).
          bool keep = !(fcc.auto_origin && p.z < origin.z - 1e-9 * period.z);
          for (int k = 0; k < 3 && keep; ++k) {
            if (box.periodic[k]) {
              // Each pore once: [lo, hi) with a round-off margin so that a point on lo and its
              // image on hi are not both (or neither) taken.
              const double tol = 1e-9 * period[k];
              keep = p[k] >= box.lo[k] - tol && p[k] < box.hi()[k] - tol;
            } else {
              keep = p[k] > box.lo[k] - R && p[k] < box.hi()[k] + R;
            }
          }
          if (keep) {
            pores.centre.push_back(box.wrap(p));
            pores.radius.push_back(R);
          }
        }
  return pores;
}

double packed_pore_volume(const RandomPores& o) { return sphere_volume(0.5 * o.spacing_ratio * o.diameter); }

PoreSet random_pores(const Box& region, const RandomPores& o, Random& rng) {
  require(o.diameter > 0.0 && std::isfinite(o.diameter), "pore_diameter", o.diameter, "> 0 m");
  require(o.count >= 1, "pores", static_cast<double>(o.count), ">= 1");
  require(o.spacing_ratio >= 0.5 && o.spacing_ratio <= 2.0, "pore_spacing", o.spacing_ratio,
          "in [0.5, 2] (minimum pore centre distance / pore diameter)");
  const double R = 0.5 * o.diameter;
  const double fraction = static_cast<double>(o.count) * packed_pore_volume(o) / region.volume();
  require(fraction < 0.7, "pore volume fraction (pores x pi (spacing D)^3/6 / region volume)", fraction,
          "< 0.7 (non-overlapping pores; use fewer pores or a larger box)");
  Box fba_box = region;
  if (o.periodic) fba_box.periodic = {true, true, true};
  FbaParams fp;
  fp.target_porosity = 1.0 - fraction;
  fp.tolerance = o.fba_tolerance;
  fp.max_iterations = o.fba_max_iterations;
  // Periodic pores fill the box to the paper's highest porosities (packed fractions up to
  // 0.65): FBA's default shrink rate stalls there with overlaps left; a slower one separates
  // them (docs/opal-build.md, "Random pores").
  constexpr double periodic_pore_shrink_rate = 1e-3;
  if (o.periodic) fp.shrink_rate = periodic_pore_shrink_rate;
  FbaResult r = fba_pack(fba_box, std::vector<double>(static_cast<std::size_t>(o.count), 1.0), fp, rng);
  if (r.status.stop != FbaStop::target_reached)
    fail_input(
        fmt::format("pores = {}: the force-biased algorithm did not separate the pores in {} iterations "
                    "(max overlap {:g}); use fewer pores{}",
                    o.count, o.fba_max_iterations, r.status.max_overlap,
                    o.periodic ? "" : " or periodic pores (pore_boundary = periodic)"));
  PoreSet pores;
  pores.centre = std::move(r.packing.position);
  // Periodic pores along the region's open axes: the image of a pore that crosses a face enters
  // at the opposite face (images of images too, for a pore at an edge or a corner).
  for (int a = 0; a < 3 && o.periodic; ++a) {
    if (region.periodic[a]) continue;
    const std::size_t n = pores.centre.size();
    for (std::size_t k = 0; k < n; ++k) {
      Vec3 image = pores.centre[k];
      if (image[a] - region.lo[a] < R)
        image[a] += region.length[a];
      else if (region.hi()[a] - image[a] < R)
        image[a] -= region.length[a];
      else
        continue;
      pores.centre.push_back(image);
    }
  }
  pores.radius.assign(pores.centre.size(), R);
  return pores;
}

Box random_pore_region(const Packing& particles, double substrate_layers) {
  require(substrate_layers >= 0.0 && substrate_layers <= 1000.0, "substrate_layers", substrate_layers,
          "in [0, 1000] particle diameters");
  require(particles.size() >= 1, "particles", 0, ">= 1 in the input packing");
  const Substrate slab = substrate_slab(particles, substrate_layers);
  double r_max = 0;
  for (double r : particles.radius) r_max = std::max(r_max, r);
  Box region = particles.box;
  if (substrate_layers == 0.0 && region.periodic[2]) return region;
  const double floor = std::max(region.lo.z, slab.top + r_max);
  region.length.z = region.hi().z - floor;
  region.lo.z = floor;
  require(region.length.z > 0.0, "substrate_layers", substrate_layers, "below the top of the box");
  return region;
}

void OpalOptions::validate() const {
  const bool fcc_given = fcc.diameter > 0.0;
  if (fcc_given == !pores.centre.empty())
    fail_input(fcc_given ? "pores: give either an FCC pore lattice or a pore list, not both"
                         : "pores: give an FCC pore lattice (pore_diameter > 0) or a non-empty pore list");
  if (fcc_given) {
    require(std::isfinite(fcc.diameter), "pore_diameter", fcc.diameter, "> 0 m");
    require(fcc.spacing_ratio >= 0.5 && fcc.spacing_ratio <= 2.0, "pore_spacing", fcc.spacing_ratio,
            "in [0.5, 2] (nearest-neighbour distance / pore diameter)");
  }
  if (pores.radius.size() != pores.centre.size()) fail_input("pores: one radius per centre");
  for (double r : pores.radius) require(r > 0.0 && std::isfinite(r), "pore radius", r, "> 0 m");
  OpalOptions copy = *this;
  io::ConfigSchema declared("build opal");
  io::add_opal_params(declared, copy);
  declared.validate();
}

PoreSet opal_pores(const Packing& particles, const OpalOptions& options) {
  options.validate();
  if (options.fcc.diameter <= 0.0) return options.pores;
  const Substrate slab = substrate_slab(particles, options.substrate_layers);
  double r_max = 0;
  for (double r : particles.radius) r_max = std::max(r_max, r);
  return fcc_pores(particles.box, options.fcc, slab.top + r_max);
}

Packing build_opal(const Packing& in, const OpalOptions& options, OpalSummary* summary,
                   const std::function<void(const std::string&, double)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  options.validate();
  in.validate();
  require(in.size() >= 1, "particles", 0, ">= 1 in the input packing");
  const Box& box = in.box;
  const std::size_t n = in.size();
  const Substrate slab = substrate_slab(in, options.substrate_layers);
  if (progress) progress("pores", 0.0);
  const PoreSet pores = opal_pores(in, options);
  double r_pore_max = 0, r_pore_sum = 0, r_max = 0;
  for (double r : pores.radius) {
    r_pore_max = std::max(r_pore_max, r);
    r_pore_sum += r;
  }
  for (double r : in.radius) r_max = std::max(r_max, r);
  const double L_coat = options.coating_thickness;
  for (int a = 0; a < 3; ++a)
    if (box.periodic[a] && box.length[a] < 2.0 * (r_pore_max + r_max))
      fail_input(
          fmt::format("box length {} = {:g} m: must be >= {:g} m (a pore diameter plus a particle "
                      "diameter) along a periodic axis",
                      "xyz"[a], box.length[a], 2.0 * (r_pore_max + r_max)));

  // Steps 2-3: pore test (eq. 1) and coating candidates (eq. 2), every pore the particle is in.
  enum : std::uint8_t { keep = 0, in_pore = 1, candidate = 2 };
  std::vector<std::uint8_t> state(n, keep);
  if (!pores.centre.empty()) {
    const CellGrid grid(box, pores.centre, std::max(r_pore_max + r_max, 1e-300));
    for (std::size_t i = 0; i < n; ++i) {
      bool inside = false, deep = false;
      grid.query(in.position[i], r_pore_max + in.radius[i], [&](int k, const Vec3& d) {
        const double L = norm(d), reach = pores.radius[static_cast<std::size_t>(k)] + in.radius[i];
        if (L <= reach) {
          inside = true;
          if (L < reach - L_coat) deep = true;
        }
      });
      if (inside) state[i] = (L_coat > 0.0 && !deep) ? candidate : in_pore;
    }
  }
  if (progress) progress("coating", 0.3);

  // Openings filter: a candidate stays coating only within opening_distance_ratio x (L_coat + R_p)
  // of a remaining silica particle's surface.
  long openings = 0;
  if (L_coat > 0.0) {
    std::vector<Vec3> silica;
    std::vector<double> silica_r;
    for (std::size_t i = 0; i < n; ++i)
      if (state[i] == keep) {
        silica.push_back(in.position[i]);
        silica_r.push_back(in.radius[i]);
      }
    const double reach_max = options.opening_distance_ratio * (L_coat + r_max) + r_max;
    const CellGrid grid(box, silica, reach_max);
    for (std::size_t i = 0; i < n; ++i) {
      if (state[i] != candidate) continue;
      const double reach = options.opening_distance_ratio * (L_coat + in.radius[i]);
      bool near = false;
      if (!silica.empty())
        grid.query(in.position[i], reach + r_max, [&](int s, const Vec3& d) {
          if (norm(d) - silica_r[static_cast<std::size_t>(s)] <= reach) near = true;
        });
      if (!near) {
        state[i] = in_pore;
        ++openings;
      }
    }
  }
  if (progress) progress("substrate", 0.5);

  // Steps 4: the model's particles, substrate slab fixed.
  Packing out;
  out.box = box;
  double v_before = 0, v_silica = 0, v_titania = 0, v_all = 0;
  long n_struct = 0, n_coat = 0, n_sub = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double v = sphere_volume(in.radius[i]);
    const bool sub = in.position[i].z < slab.top;
    if (!sub) v_before += v;
    if (state[i] == in_pore) continue;
    int t = state[i] == candidate ? particle_type::coating : particle_type::structural;
    if (sub) t = particle_type::substrate;
    out.add(in.position[i], in.radius[i], t);
    out.fixed.push_back(sub ? 1 : 0);
    v_all += v;
    if (t == particle_type::substrate)
      ++n_sub;
    else if (t == particle_type::coating)
      ++n_coat, v_titania += v;
    else
      ++n_struct, v_silica += v;
  }
  if (progress) progress("bonds", 0.6);

  // Step 5: bonds.
  BondingOptions bo;
  bo.cutoff_ratio = options.bond_cutoff_ratio;
  bo.material_of_types = opal_bond_material_of;
  bo.threads = options.threads;
  if (out.size() > 0) add_bonds(out, bo);
  if (progress) progress("done", 1.0);

  if (summary) {
    OpalSummary& s = *summary;
    s = OpalSummary{};
    s.input_particles = static_cast<long>(n);
    s.particles = static_cast<long>(out.size());
    s.structural = n_struct;
    s.coating = n_coat;
    s.substrate = n_sub;
    s.removed = static_cast<long>(n - out.size());
    s.coating_openings = openings;
    s.pores = static_cast<long>(pores.size());
    s.bonds = static_cast<long>(out.bonds.size());
    for (std::size_t b = 0; b < out.bonds.size(); ++b) {
      const int m = out.bonds.material[b];
      if (m >= 0 && m < 3) ++s.bonds_by_material[static_cast<std::size_t>(m)];
      const auto& img = out.bonds.image[b];
      if (img[0] != 0 || img[1] != 0 || img[2] != 0) ++s.periodic_bonds;
    }
    s.mean_coordination = out.size() ? 2.0 * static_cast<double>(s.bonds) / static_cast<double>(out.size()) : 0.0;
    s.porosity = v_before > 0 ? 1.0 - (v_silica + v_titania) / v_before : 0.0;
    s.particle_porosity = 1.0 - v_all / box.volume();
    s.density =
        v_before > 0 ? (options.silica_density * v_silica + options.titania_density * v_titania) / v_before : 0.0;
    s.pore_diameter = pores.size() ? 2.0 * r_pore_sum / static_cast<double>(pores.size()) : 0.0;
    s.mean_particle_diameter = slab.mean_diameter;
    s.substrate_top = slab.top;
    s.bond_radius_ratio = options.bond_radius_ratio;
    s.lattice_commensurate = options.fcc.diameter > 0.0 ? commensurate(box, fcc_pore_period(options.fcc)) : true;
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return out;
}

}  // namespace packlab::generate
