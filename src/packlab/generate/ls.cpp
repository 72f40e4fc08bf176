#include "packlab/generate/ls.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "packlab/core/error.hpp"
#include "packlab/core/neighbor_list.hpp"
#include "packlab/core/spatial_sort.hpp"

namespace packlab::generate {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double cell_margin = 1e-9;  // relative slack between the largest contact distance and a cell edge

int floor_div(int a, int n) { return a >= 0 ? a / n : -((-a + n - 1) / n); }

// Collision time (eq. 8) if it is below `horizon`, else +inf. f(t) = A t^2 + 2 B t + C =
// |dx + dv t|^2 - (sigma + sdot t)^2. Lower bounds reject most pairs without sqrt or division:
// for B < 0 and A >= 0 the root C / (-B + sqrt(B^2 - AC)) is >= C / (-2B); for B >= 0 and A < 0
// the root (B + sqrt(B^2 - AC)) / (-A) is >= 2B / (-A) when C >= 0.
[[gnu::always_inline]] inline double collision_time_below(const Vec3& dx, const Vec3& dv, double sigma,
                                                          double sdot, double horizon) {
  const double a = norm2(dv) - sdot * sdot;
  const double b = dot(dx, dv) - sigma * sdot;
  const double c = norm2(dx) - sigma * sigma;
  if (b < 0.0) {
    if (c <= 0.0) return 0.0;
    if (a >= 0.0 && c >= -2.0 * b * horizon) return inf;
    const double disc = b * b - a * c;
    if (disc < 0.0) return inf;
    return c / (-b + std::sqrt(disc));
  }
  if (a >= 0.0) return inf;
  if (c >= 0.0 && 2.0 * b >= -a * horizon) return inf;
  const double disc = std::max(0.0, b * b - a * c);
  return (b + std::sqrt(disc)) / (-a);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Size classes

SizeClasses SizeClasses::from_options(const std::vector<double>& sizes, const std::vector<double>& number_fractions,
                                      const std::vector<double>& volume_fractions) {
  if (!number_fractions.empty() && !volume_fractions.empty())
    fail_input("--number-fractions and --volume-fractions: give one of them");
  SizeClasses c;
  c.sizes = sizes;
  c.volume_fractions = !volume_fractions.empty();
  c.fractions = c.volume_fractions ? volume_fractions : number_fractions;
  c.validate();
  return c;
}

void SizeClasses::validate() const {
  require(!sizes.empty(), "sizes", 0, "a list of at least one relative diameter");
  for (double s : sizes) require(s > 0.0 && std::isfinite(s), "sizes", s, "> 0 (relative diameters)");
  if (!fractions.empty()) {
    require(fractions.size() == sizes.size(), volume_fractions ? "volume_fractions" : "number_fractions",
            static_cast<double>(fractions.size()), fmt::format("one value per size ({})", sizes.size()));
    double sum = 0.0;
    for (double f : fractions) {
      require(f >= 0.0 && std::isfinite(f), volume_fractions ? "volume_fractions" : "number_fractions", f, ">= 0");
      sum += f;
    }
    require(sum > 0.0, volume_fractions ? "volume_fractions" : "number_fractions", sum, "a positive sum");
  }
}

std::vector<double> SizeClasses::number_fractions() const {
  validate();
  std::vector<double> x(sizes.size(), 1.0);
  if (!fractions.empty()) {
    for (std::size_t k = 0; k < sizes.size(); ++k)
      x[k] = volume_fractions ? fractions[k] / (sizes[k] * sizes[k] * sizes[k]) : fractions[k];
  }
  const double sum = std::accumulate(x.begin(), x.end(), 0.0);
  for (double& v : x) v /= sum;
  return x;
}

std::vector<long> SizeClasses::counts(long n) const {
  const std::vector<double> x = number_fractions();
  std::vector<long> c(x.size());
  std::vector<std::pair<double, std::size_t>> rest;
  long total = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double exact = x[k] * static_cast<double>(n);
    c[k] = static_cast<long>(std::floor(exact));
    total += c[k];
    rest.emplace_back(exact - std::floor(exact), k);
  }
  std::stable_sort(rest.begin(), rest.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t r = 0; total < n; ++r, ++total) ++c[rest[r % rest.size()].second];
  return c;
}

// ---------------------------------------------------------------------------------------------
// Parameters

void LsParams::validate() const {
  require(growth_rate >= 0.0 && std::isfinite(growth_rate), "growth_rate", growth_rate, ">= 0");
  require(target_volume_fraction >= 0.0 && target_volume_fraction < 1.0, "target_volume_fraction",
          target_volume_fraction, "in [0, 1) (0 = grow until jammed)");
  require(max_reduced_pressure > 1.0, "max_reduced_pressure", max_reduced_pressure, "> 1");
  require(events_per_block >= 0.01 && events_per_block <= 1e6, "events_per_block", events_per_block,
          "in [0.01, 1e6] events per particle");
  require(max_blocks >= 0, "max_blocks", static_cast<double>(max_blocks), ">= 0");
  require(max_events_per_particle > 0.0, "max_events_per_particle", max_events_per_particle, "> 0");
  require(separation_boost >= 1.0 && separation_boost <= 100.0, "separation_boost", separation_boost,
          "in [1, 100]");
  require(neighbor_skin > 0.0 && neighbor_skin <= 1.0, "neighbor_skin", neighbor_skin, "in (0, 1] diameters");
  if (growth_rate == 0.0)
    require(max_blocks > 0, "max_blocks", static_cast<double>(max_blocks),
            "> 0 when growth_rate = 0 (nothing else would stop the run)");
}

std::string ls_stop_name(LsStop stop) {
  switch (stop) {
    case LsStop::target_reached: return "target_reached";
    case LsStop::jammed: return "jammed";
    case LsStop::max_blocks: return "max_blocks";
    case LsStop::max_events: return "max_events";
  }
  return "?";
}

// ---------------------------------------------------------------------------------------------
// Two-body kernels

double LsSimulation::collision_time(const Vec3& dx, const Vec3& dv, double sigma, double sigma_dot) {
  // Approaching surfaces: the smaller positive root, written without cancellation. Receding
  // surfaces meet again only if the growth wins (A < 0), at the larger root.
  return collision_time_below(dx, dv, sigma, sigma_dot, inf);
}

void LsSimulation::collide(Vec3& vi, Vec3& vj, const Vec3& n, double sigma_dot, double boost) {
  const double u = dot(vj - vi, n);
  const double dvn = u - boost * sigma_dot;
  vi += n * dvn;
  vj -= n * dvn;
}

// ---------------------------------------------------------------------------------------------
// Set-up

LsSimulation::LsSimulation(const Packing& start, const LsParams& params, Random& rng) : params_(params) {
  params_.validate();
  start.validate();
  for (int a = 0; a < 3; ++a)
    if (!start.box.periodic[a])
      fail_input(fmt::format("box periodic along {} = false: Lubachevsky-Stillinger growth needs a box periodic "
                             "on every axis",
                             "xyz"[a]));
  if (start.size() < 2) fail_input("particles = " + std::to_string(start.size()) + ": must be >= 2");
  const double ratio = min_contact_ratio(start);
  require(ratio >= 1.0 - 1e-9, "min contact ratio d/(r_i+r_j)", ratio,
          ">= 1: the starting packing has overlapping spheres (hard spheres cannot grow from it)");
  const double s_start = std::cbrt(start.volume_fraction());
  std::vector<double> unit(start.size());
  for (std::size_t i = 0; i < start.size(); ++i) unit[i] = start.radius[i] / s_start;
  init(start.box, start.position, std::move(unit), s_start, rng);
  skin_rel_ = params_.neighbor_skin;
  if (!start.velocity.empty()) {
    // Keep the incoming velocities' directions and relative magnitudes; rescale to kT below.
    bool any = false;
    for (const auto& v : start.velocity) any = any || norm2(v) > 0.0;
    if (any) {
      for (std::size_t i = 0; i < body_.size(); ++i) body_[i].v = start.velocity[id_[i]];
      double sum = 0.0;
      for (const auto& b : body_) sum += norm2(b.v);
      const double f = std::sqrt(3.0 * static_cast<double>(body_.size()) * v_thermal_ * v_thermal_ / sum);
      for (auto& b : body_) b.v *= f;
    }
  }
}

LsSimulation::LsSimulation(const Box& box, std::vector<Vec3> points, std::vector<double> unit_radius,
                           const LsParams& params, Random& rng)
    : params_(params) {
  params_.validate();
  for (int a = 0; a < 3; ++a)
    if (!box.periodic[a])
      fail_input(fmt::format("box periodic along {} = false: Lubachevsky-Stillinger growth needs a box periodic "
                             "on every axis",
                             "xyz"[a]));
  if (points.size() < 2) fail_input("particles = " + std::to_string(points.size()) + ": must be >= 2");
  if (unit_radius.size() != points.size()) throw std::logic_error("LsSimulation: radius and point counts differ");
  init(box, std::move(points), std::move(unit_radius), 0.0, rng);
  skin_rel_ = params_.neighbor_skin;
}

void LsSimulation::init(const Box& box, std::vector<Vec3> points, std::vector<double> unit_radius, double s0,
                        Random& rng) {
  box_ = box;
  origin_ = box.lo;
  box_.lo = {0, 0, 0};
  const std::size_t n = points.size();
  for (double r : unit_radius) require(r > 0.0 && std::isfinite(r), "radius", r, "> 0");
  // Classes: distinct radii, largest first.
  std::vector<double> distinct = unit_radius;
  std::sort(distinct.begin(), distinct.end(), std::greater<>());
  class_rho_.clear();
  for (double r : distinct)
    if (class_rho_.empty() || r < class_rho_.back() * (1.0 - 1e-12)) class_rho_.push_back(r);
  if (class_rho_.size() > 64)
    fail_input(fmt::format("distinct radii = {}: Lubachevsky-Stillinger growth supports at most 64 size classes",
                           class_rho_.size()));
  nclass_ = static_cast<int>(class_rho_.size());
  body_.resize(n);
  cls_.resize(n);
  id_.resize(n);
  count_.assign(n, 0);
  ev_.resize(n);
  cell_.resize(n);
  slot_.resize(n);
  cc_.resize(n);
  double volume = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    Body& b = body_[i];
    b.x = box_.wrap(points[i] - origin_);
    b.t = 0.0;
    b.rho = unit_radius[i];
    int k = 0;
    while (k + 1 < nclass_ && unit_radius[i] < class_rho_[k] * (1.0 - 1e-12)) ++k;
    cls_[i] = k;
    b.rho = class_rho_[k];
    id_[i] = static_cast<int>(i);
    volume += 4.0 / 3.0 * std::numbers::pi * b.rho * b.rho * b.rho;
  }
  phi1_ = volume / box_.volume();
  s0_ = s0;
  v_thermal_ = 2.0 * class_rho_[0];
  // Maxwell velocities, zero total momentum, kinetic energy exactly 3/2 N kT.
  Vec3 mean{};
  for (auto& b : body_) {
    b.v = {rng.normal() * v_thermal_, rng.normal() * v_thermal_, rng.normal() * v_thermal_};
    mean += b.v;
  }
  mean *= 1.0 / static_cast<double>(n);
  double sum = 0.0;
  for (auto& b : body_) {
    b.v -= mean;
    sum += norm2(b.v);
  }
  const double f = std::sqrt(3.0 * static_cast<double>(n) * v_thermal_ * v_thermal_ / sum);
  for (auto& b : body_) b.v *= f;
  // The minimum image must be unique at contact: largest contact distance < half the box.
  const double phi_final = params_.target_volume_fraction > 0.0 ? params_.target_volume_fraction : 0.9;
  const double s_final = std::cbrt(phi_final / phi1_);
  const double l_min = std::min({box_.length.x, box_.length.y, box_.length.z});
  if (4.0 * class_rho_[0] * s_final >= l_min)
    fail_input(fmt::format("box edge = {:g} m is less than two largest diameters ({:g} m) at volume fraction {:g}; "
                           "use more particles",
                           l_min, 4.0 * class_rho_[0] * s_final, phi_final));
  status_ = LsStatus{};
  status_.scale = s0_;
  status_.volume_fraction = phi1_ * s0_ * s0_ * s0_;
}

void LsSimulation::set_params(const LsParams& params) {
  params.validate();
  params_ = params;
}

void LsSimulation::set_positions(const std::vector<Vec3>& position) {
  if (position.size() != body_.size()) throw std::logic_error("LsSimulation::set_positions: wrong particle count");
  for (std::size_t i = 0; i < body_.size(); ++i) {
    body_[i].x = box_.wrap(position[id_[i]] - origin_);
    body_[i].t = 0.0;
  }
}

// ---------------------------------------------------------------------------------------------
// Cells of bounding-sphere centres, one grid per class, rebuilt every block.

void LsSimulation::build_grids() {
  const double g = params_.growth_rate;
  const double s_want = g > 0.0 ? s0_ * 1.02 : s0_;
  std::vector<long> per_class(nclass_, 0);
  for (int k : cls_) ++per_class[k];
  grid_.resize(nclass_);
  skin_.assign(nclass_, 0.0);
  bound_cap_.assign(nclass_, 0.0);
  // Skins relative to the current diameter, at least that of s = 0.2 (growth from points).
  const double l_min0 = std::min({box_.length.x, box_.length.y, box_.length.z});
  // Keep 2 x (largest bounding radius) within a quarter box.
  skin_rel_ = std::min(skin_rel_, std::max(0.005, (0.2 * l_min0 - class_rho_[0] * s_want) /
                                                      (2.0 * class_rho_[0] * std::max(s0_, 0.2))));
  for (int k = 0; k < nclass_; ++k) skin_[k] = skin_rel_ * 2.0 * class_rho_[k] * std::max(s0_, 0.2);
  double s_cap = inf;
  for (int k = 0; k < nclass_; ++k) {
    Grid& gr = grid_[k];
    const double d = 2.0 * (class_rho_[k] * s_want + skin_[k]) * (1.0 + cell_margin);
    double want[3];
    for (int a = 0; a < 3; ++a) want[a] = std::clamp(std::floor(box_.length[a] / d), 1.0, 1e6);
    const double max_cells = 2.0 * static_cast<double>(per_class[k]) + 27.0;
    while (want[0] * want[1] * want[2] > max_cells) {
      const int a = want[0] >= want[1] && want[0] >= want[2] ? 0 : (want[1] >= want[2] ? 1 : 2);
      want[a] = std::max(1.0, std::floor(want[a] / 2.0));
    }
    for (int a = 0; a < 3; ++a) {
      gr.n[a] = static_cast<int>(want[a]);
      gr.h[a] = box_.length[a] / gr.n[a];
      s_cap = std::min(s_cap, (gr.h[a] / (2.0 * (1.0 + cell_margin)) - skin_[k]) / class_rho_[k]);
    }
  }
  // Unique minimum image at contact, and neighbour images within one box length.
  const double l_min = std::min({box_.length.x, box_.length.y, box_.length.z});
  s_cap = std::min(s_cap, (l_min / 4.0 * (1.0 - cell_margin) - skin_[0]) / class_rho_[0]);
  if (g > 0.0 && s_cap <= s0_)
    fail_input(fmt::format("box edge = {:g} m: too small for the spheres at volume fraction {:g}; use more particles",
                           l_min, phi1_ * s0_ * s0_ * s0_));
  for (int k = 0; k < nclass_; ++k) bound_cap_[k] = class_rho_[k] * std::max(s_cap, s0_) + skin_[k];
  reach_.assign(static_cast<std::size_t>(nclass_) * nclass_, 0.0);
  for (int k = 0; k < nclass_; ++k)
    for (int m = 0; m < nclass_; ++m)
      reach_[k * nclass_ + m] = (bound_cap_[k] + bound_cap_[m]) * (1.0 + cell_margin);
  // Fill.
  std::vector<int> occupancy;
  for (int k = 0; k < nclass_; ++k) {
    Grid& gr = grid_[k];
    occupancy.assign(static_cast<std::size_t>(gr.n[0]) * gr.n[1] * gr.n[2], 0);
    for (std::size_t i = 0; i < body_.size(); ++i) {
      if (cls_[i] != k) continue;
      auto& c = cc_[i];
      for (int a = 0; a < 3; ++a)
        c[a] = std::clamp(static_cast<int>(std::floor(body_[i].x[a] / gr.h[a])), 0, gr.n[a] - 1);
      cell_[i] = c[0] + gr.n[0] * (c[1] + gr.n[1] * c[2]);
      ++occupancy[cell_[i]];
    }
    int most = 0;
    for (int o : occupancy) most = std::max(most, o);
    gr.cap = std::max(8, most + 4);
    gr.fill.assign(occupancy.size(), 0);
    gr.slots.assign(occupancy.size() * gr.cap, -1);
  }
  for (std::size_t i = 0; i < body_.size(); ++i) insert(static_cast<int>(i));
  // Block end: the target or the largest scale these cells allow.
  t_target_ = inf;
  const double phi_t = params_.target_volume_fraction;
  if (phi_t > 0.0 && g > 0.0) t_target_ = (std::cbrt(phi_t / phi1_) - s0_) / g;
  const double t_cap = g > 0.0 ? (s_cap - s0_) / g : inf;
  target_in_block_ = t_target_ <= t_cap;
  t_end_ = std::min(t_target_, t_cap);
}

void LsSimulation::insert(int i) {
  Grid& gr = grid_[cls_[i]];
  const int cell = cell_[i];
  if (gr.fill[cell] == gr.cap) {  // rare: double the capacity of every cell
    const int cap2 = gr.cap * 2;
    std::vector<int> slots(gr.fill.size() * cap2, -1);
    for (std::size_t c = 0; c < gr.fill.size(); ++c)
      std::copy_n(gr.slots.begin() + static_cast<long>(c * gr.cap), gr.fill[c],
                  slots.begin() + static_cast<long>(c * cap2));
    gr.slots.swap(slots);
    gr.cap = cap2;
  }
  const int s = gr.fill[cell]++;
  gr.slots[static_cast<std::size_t>(cell) * gr.cap + s] = i;
  slot_[i] = s;
}

void LsSimulation::remove(int i) {
  Grid& gr = grid_[cls_[i]];
  const int cell = cell_[i];
  const int last = --gr.fill[cell];
  int* base = gr.slots.data() + static_cast<std::size_t>(cell) * gr.cap;
  const int moved = base[last];
  base[slot_[i]] = moved;
  slot_[moved] = slot_[i];
}

// ---------------------------------------------------------------------------------------------
// Neighbour lists (symmetric: (j, image) in i's list <=> (i, -image) in j's list).

void LsSimulation::add_neighbor(int i, std::uint32_t entry) {
  const int k = cls_[i];
  if (list_fill_[i] == list_cap_[k]) {  // rare: grow this class's capacity, re-layout
    std::vector<int> cap2 = list_cap_;
    cap2[k] *= 2;
    std::vector<std::size_t> base2(body_.size());
    std::size_t total = 0;
    for (std::size_t q = 0; q < body_.size(); ++q) {
      base2[q] = total;
      total += cap2[cls_[q]];
    }
    std::vector<std::uint32_t> list2(total);
    for (std::size_t q = 0; q < body_.size(); ++q)
      std::copy_n(list_.begin() + static_cast<long>(list_base_[q]), list_fill_[q],
                  list2.begin() + static_cast<long>(base2[q]));
    list_.swap(list2);
    list_base_.swap(base2);
    list_cap_ = cap2;
  }
  list_[list_base_[i] + list_fill_[i]++] = entry;
}

void LsSimulation::drop_neighbor(int i, std::uint32_t entry) {
  std::uint32_t* l = list_.data() + list_base_[i];
  const int n = list_fill_[i];
  for (int q = 0; q < n; ++q)
    if (l[q] == entry) {
      l[q] = l[n - 1];
      --list_fill_[i];
      return;
    }
  throw std::logic_error("LsSimulation: neighbour lists are not symmetric");
}

void LsSimulation::find_neighbors(int i, bool only_greater) {
  const int k = cls_[i];
  const Grid& gk = grid_[k];
  const auto& c = cc_[i];
  const Vec3 ci = center_[i];
  const double bi = bound_[i];
  for (int m = 0; m < nclass_; ++m) {
    const Grid& gm = grid_[m];
    const double reach = reach_[k * nclass_ + m];
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      if (m == k && reach <= gk.h[a]) {
        lo[a] = c[a] - 1;
        hi[a] = c[a] + 1;
      } else {
        lo[a] = static_cast<int>(std::floor((c[a] * gk.h[a] - reach) / gm.h[a]));
        hi[a] = static_cast<int>(std::floor(((c[a] + 1) * gk.h[a] + reach) / gm.h[a]));
      }
    }
    for (int uz = lo[2]; uz <= hi[2]; ++uz) {
      const int sz = floor_div(uz, gm.n[2]);
      const int wz = uz - sz * gm.n[2];
      for (int uy = lo[1]; uy <= hi[1]; ++uy) {
        const int sy = floor_div(uy, gm.n[1]);
        const int wy = uy - sy * gm.n[1];
        const int row = gm.n[0] * (wy + gm.n[1] * wz);
        for (int ux = lo[0]; ux <= hi[0]; ++ux) {
          const int sx = floor_div(ux, gm.n[0]);
          const int wx = ux - sx * gm.n[0];
          if (sx < -1 || sx > 1 || sy < -1 || sy > 1 || sz < -1 || sz > 1)
            throw std::logic_error("LsSimulation: neighbour beyond the first periodic image");
          const int code = image_code(sx, sy, sz);
          const Vec3& off = offset_[code];
          const int cell = wx + row;
          const int fill = gm.fill[cell];
          const int* members = gm.slots.data() + static_cast<std::size_t>(cell) * gm.cap;
          for (int q = 0; q < fill; ++q) {
            const int j = members[q];
            if (j == i || (only_greater && j < i)) continue;
            const Vec3 d = center_[j] + off - ci;
            const double r = bi + bound_[j];
            if (norm2(d) < r * r) {
              add_neighbor(i, static_cast<std::uint32_t>(j) * 32u + static_cast<std::uint32_t>(code));
              add_neighbor(j, static_cast<std::uint32_t>(i) * 32u + static_cast<std::uint32_t>(26 - code));
            }
          }
        }
      }
    }
  }
}

void LsSimulation::build_lists() {
  const std::size_t n = body_.size();
  const double s = s0_;
  for (int c = 0; c < 27; ++c) offset_[c] = box_.shift_vector(image_of_code(c));
  center_.resize(n);
  bound_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    center_[i] = body_[i].x;  // wrapped by sync_all
    bound_[i] = body_[i].rho * s + skin_[cls_[i]];
  }
  if (list_cap_.size() != static_cast<std::size_t>(nclass_)) list_cap_.assign(nclass_, 16);
  list_base_.resize(n);
  list_fill_.assign(n, 0);
  std::size_t total = 0;
  for (std::size_t q = 0; q < n; ++q) {
    list_base_[q] = total;
    total += list_cap_[cls_[q]];
  }
  list_.assign(total, 0);
  for (int i = 0; i < static_cast<int>(n); ++i) find_neighbors(i, true);
}

void LsSimulation::transfer(int i) {
  Body& b = body_[i];
  // Leave the old neighbours.
  const std::uint32_t* l = list_.data() + list_base_[i];
  for (int q = 0; q < list_fill_[i]; ++q) {
    const std::uint32_t e = l[q];
    drop_neighbor(static_cast<int>(e >> 5), static_cast<std::uint32_t>(i) * 32u + (26u - (e & 31u)));
  }
  list_fill_[i] = 0;
  // Re-centre the bounding sphere at the (wrapped) current position.
  b.x = box_.wrap(b.x);
  center_[i] = b.x;
  bound_[i] = b.rho * s_at(b.t) + skin_[cls_[i]];
  remove(i);
  const Grid& gr = grid_[cls_[i]];
  auto& c = cc_[i];
  for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>(std::floor(b.x[a] / gr.h[a])), 0, gr.n[a] - 1);
  cell_[i] = c[0] + gr.n[0] * (c[1] + gr.n[1] * c[2]);
  insert(i);
  find_neighbors(i, false);
}

// ---------------------------------------------------------------------------------------------
// Event calendar: indexed binary min-heap of one pending event per particle.

void LsSimulation::heap_build() {
  const int n = static_cast<int>(body_.size());
  hkey_.resize(n);
  hid_.resize(n);
  hpos_.resize(n);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return ev_[a].time < ev_[b].time; });
  for (int k = 0; k < n; ++k) {  // a sorted array is a heap
    hid_[k] = order[k];
    hkey_[k] = ev_[order[k]].time;
    hpos_[order[k]] = k;
  }
}

void LsSimulation::heap_update(int i) {
  const double key = ev_[i].time;
  int k = hpos_[i];
  const int n = static_cast<int>(hid_.size());
  double* hk = hkey_.data();
  int* hi = hid_.data();
  int* hp = hpos_.data();
  // up
  while (k > 0) {
    const int parent = (k - 1) >> 1;
    if (hk[parent] <= key) break;
    hk[k] = hk[parent];
    hi[k] = hi[parent];
    hp[hi[k]] = k;
    k = parent;
  }
  // down
  for (;;) {
    int child = 2 * k + 1;
    if (child >= n) break;
    if (child + 1 < n && hk[child + 1] < hk[child]) ++child;
    if (hk[child] >= key) break;
    hk[k] = hk[child];
    hi[k] = hi[child];
    hp[hi[k]] = k;
    k = child;
  }
  hk[k] = key;
  hi[k] = i;
  hp[i] = k;
}

// ---------------------------------------------------------------------------------------------
// Prediction: earliest collision with a neighbour, or the transfer time.

void LsSimulation::predict(int i) {
  const Body bi = body_[i];
  const double now = bi.t;
  const double g = params_.growth_rate;
  const double s = s_at(now);
  // Transfer: |x + v t - c| = w - rho g t with w = bound - radius now.
  double tau_tr;
  {
    const Vec3 dx = bi.x - center_[i];
    const double w = bound_[i] - bi.rho * s;
    const double wdot = -bi.rho * g;
    const double a = norm2(bi.v) - wdot * wdot;
    const double b = dot(dx, bi.v) - w * wdot;
    const double c = norm2(dx) - w * w;
    if (c >= 0.0 || w <= 0.0) {
      tau_tr = 0.0;
    } else {
      const double disc = b * b - a * c;
      if (b > 0.0 && disc >= 0.0) {
        tau_tr = -c / (b + std::sqrt(disc));
      } else if (a > 0.0) {
        tau_tr = (std::sqrt(disc) - b) / a;
      } else {
        tau_tr = inf;
      }
      if (g > 0.0) tau_tr = std::min(tau_tr, w / (bi.rho * g));
    }
  }
  double best = now + tau_tr;
  int partner = -1;
  const Body* bodies = body_.data();
  const Event* ev = ev_.data();
  const std::uint32_t* l = list_.data() + list_base_[i];
  const int fill = list_fill_[i];
  for (int q = 0; q < fill; ++q) {
    const std::uint32_t e = l[q];
    const int j = static_cast<int>(e >> 5);
    const Vec3& off = offset_[e & 31u];
    const Body& bj = bodies[j];
    const double dtj = now - bj.t;
    const Vec3 dx{bj.x.x + bj.v.x * dtj + off.x - bi.x.x, bj.x.y + bj.v.y * dtj + off.y - bi.x.y,
                  bj.x.z + bj.v.z * dtj + off.z - bi.x.z};
    const Vec3 dv = bj.v - bi.v;
    const double sig1 = bi.rho + bj.rho;
    const double tau = collision_time_below(dx, dv, sig1 * s, sig1 * g, best - now);
    // A collision after j's own next event is left to j: j predicts again then.
    if (now + tau < best && now + tau <= ev[j].time) {
      best = now + tau;
      partner = j;
    }
  }
  Event& e = ev_[i];
  e.time = best;
  e.partner = partner;
  e.count = partner >= 0 ? count_[partner] : 0;
  if (!hid_.empty()) heap_update(i);
}

// ---------------------------------------------------------------------------------------------
// Blocks

void LsSimulation::sync_all(double t) {
  for (auto& b : body_) {
    b.x += b.v * (t - b.t);
    b.x = box_.wrap(b.x);
    b.t = 0.0;
  }
}

void LsSimulation::start_block() {
  // Morton order: neighbours in space are neighbours in memory.
  const double cell = std::max(2.0 * class_rho_[0] * std::max(s0_, 0.05),
                               std::min({box_.length.x, box_.length.y, box_.length.z}) * 1e-4);
  std::vector<Vec3> pos(body_.size());
  for (std::size_t i = 0; i < body_.size(); ++i) pos[i] = body_[i].x;
  const std::vector<int> order = spatial_order(box_, pos, cell);
  {
    std::vector<Body> b2(body_.size());
    std::vector<int> c2(body_.size()), id2(body_.size());
    std::vector<std::uint32_t> n2(body_.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
      b2[k] = body_[order[k]];
      c2[k] = cls_[order[k]];
      id2[k] = id_[order[k]];
      n2[k] = count_[order[k]];
    }
    body_.swap(b2);
    cls_.swap(c2);
    id_.swap(id2);
    count_.swap(n2);
  }
  build_grids();
  build_lists();
  hid_.clear();
  for (auto& e : ev_) e = Event{inf, -2, 0};
  for (int i = 0; i < static_cast<int>(body_.size()); ++i) predict(i);
  heap_build();
  virial_ = 0.0;
}

bool LsSimulation::run_block() {
  const long long n = static_cast<long long>(body_.size());
  const long long budget = std::max<long long>(1, static_cast<long long>(params_.events_per_block * static_cast<double>(n)));
  const double boost = params_.separation_boost;
  const double g = params_.growth_rate;
  const long long collisions0 = status_.collisions, transfers0 = status_.transfers;
  long long done = 0;
  double now = 0.0;
  bool reached_end = false;
  Body* bodies = body_.data();
  while (done < budget) {
    const int i = hid_[0];
    const Event e = ev_[i];
    if (e.time >= t_end_) {
      reached_end = std::isfinite(t_end_);
      if (reached_end) now = t_end_;
      break;
    }
    now = e.time;
    Body& bi = bodies[i];
    if (e.partner >= 0) {
      const int j = e.partner;
      if (count_[j] != e.count) {  // partner changed velocity since: predict again
        ++status_.stale;
        bi.x += bi.v * (now - bi.t);
        bi.t = now;
        predict(i);
        continue;
      }
      Body& bj = bodies[j];
      bi.x += bi.v * (now - bi.t);
      bi.t = now;
      bj.x += bj.v * (now - bj.t);
      bj.t = now;
      Vec3 d = bj.x - bi.x;
      for (int a = 0; a < 3; ++a) {
        const double l = box_.length[a];
        if (d[a] > 0.5 * l) d[a] -= l;
        else if (d[a] < -0.5 * l) d[a] += l;
      }
      const double r = norm(d);
      const Vec3 nrm = d * (1.0 / r);
      const double sig1 = bi.rho + bj.rho;
      const double u = dot(bj.v - bi.v, nrm);
      virial_ += std::abs(u) * r;  // exchanged momentum (unit masses) times distance, growth part excluded
      collide(bi.v, bj.v, nrm, sig1 * g, boost);
      ++count_[i];
      ++count_[j];
      ++status_.collisions;
      ++done;
      predict(i);
      predict(j);
    } else if (e.partner == -1) {
      bi.x += bi.v * (now - bi.t);
      bi.t = now;
      transfer(i);
      ++status_.transfers;
      ++done;
      predict(i);
    } else {
      break;  // nothing can happen any more
    }
  }
  sync_all(now);
  {  // adapt the skin: transfers cost a cell search, large lists cost every prediction
    const double c = static_cast<double>(status_.collisions - collisions0);
    const double t = static_cast<double>(status_.transfers - transfers0);
    double fill = 0.0;
    for (int x : list_fill_) fill += x;
    fill /= static_cast<double>(n);
    if (t > 0.5 * c && fill < 12.0) skin_rel_ = std::min(2.0, skin_rel_ * 1.5);
    else if (t < 0.1 * c || fill > 20.0) skin_rel_ = std::max(0.005, skin_rel_ * 0.8);
  }
  status_.time += now;
  ++status_.blocks;
  double sum_v2 = 0.0;
  for (const auto& b : body_) sum_v2 += norm2(b.v);
  const double kinetic = 0.5 * sum_v2;
  status_.reduced_pressure = now > 0.0 ? 1.0 + virial_ / (2.0 * kinetic * now) : 1.0;
  const double f = std::sqrt(3.0 * static_cast<double>(n) * v_thermal_ * v_thermal_ / sum_v2);
  for (auto& b : body_) b.v *= f;
  bool stop = false;
  if (reached_end && target_in_block_) {
    s0_ = std::cbrt(params_.target_volume_fraction / phi1_);
    status_.stop = LsStop::target_reached;
    stop = true;
  } else {
    s0_ = s_at(now);
  }
  status_.scale = s0_;
  status_.volume_fraction = phi1_ * s0_ * s0_ * s0_;
  if (!stop && status_.reduced_pressure >= params_.max_reduced_pressure) {
    status_.stop = LsStop::jammed;
    stop = true;
  }
  if (!stop && static_cast<double>(status_.events()) >= params_.max_events_per_particle * static_cast<double>(n)) {
    status_.stop = LsStop::max_events;
    stop = true;
  }
  return !stop;
}

LsStatus LsSimulation::run(const std::function<void(const LsStatus&)>& on_block) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  const double seconds0 = status_.seconds, cpu0 = status_.cpu_seconds;
  if (params_.target_volume_fraction > 0.0 && status_.volume_fraction >= params_.target_volume_fraction) {
    status_.stop = LsStop::target_reached;
    return status_;
  }
  long blocks = 0;
  for (;;) {
    start_block();
    const bool go_on = run_block();
    ++blocks;
    status_.seconds = seconds0 + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    status_.cpu_seconds = cpu0 + static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    if (on_block) on_block(status_);
    if (!go_on) break;
    if (params_.max_blocks > 0 && blocks >= params_.max_blocks) {
      status_.stop = LsStop::max_blocks;
      break;
    }
  }
  return status_;
}

Packing LsSimulation::packing() {
  Packing p;
  Box box = box_;
  box.lo = origin_;
  p.box = box;
  const std::size_t n = body_.size();
  p.position.resize(n);
  p.radius.resize(n);
  p.type.assign(n, particle_type::structural);
  p.velocity.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Body& b = body_[i];
    const int o = id_[i];
    p.position[o] = box.wrap(b.x + b.v * (0.0 - b.t) + origin_);
    p.radius[o] = b.rho * s0_;
    p.velocity[o] = b.v;
  }
  const double ratio = min_contact_ratio(p);
  overlap_correction_ = 0.0;
  if (ratio < 1.0) {
    // Round-off contacts: shrink all radii so that no pair overlaps.
    const double f = ratio * (1.0 - 4.0 * std::numeric_limits<double>::epsilon());
    for (double& r : p.radius) r *= f;
    overlap_correction_ = 1.0 - f;
  }
  return p;
}

// ---------------------------------------------------------------------------------------------

LsStart make_ls_start(long particles, const SizeClasses& classes, double radius, double volume_fraction,
                      Random& rng) {
  classes.validate();
  require(particles >= 2 && particles <= 100'000'000, "particles", static_cast<double>(particles), "in [2, 1e8]");
  require(radius > 0.0 && std::isfinite(radius), "radius", radius, "> 0 m");
  require(volume_fraction > 0.0 && volume_fraction < 1.0, "volume_fraction", volume_fraction, "in (0, 1)");
  const std::vector<long> count = classes.counts(particles);
  const double size_max = *std::max_element(classes.sizes.begin(), classes.sizes.end());
  double volume = 0.0;
  std::vector<double> r(classes.sizes.size());
  for (std::size_t k = 0; k < r.size(); ++k) {
    r[k] = radius * classes.sizes[k] / size_max;
    volume += static_cast<double>(count[k]) * 4.0 / 3.0 * std::numbers::pi * r[k] * r[k] * r[k];
  }
  const double edge = std::cbrt(volume / volume_fraction);
  LsStart s;
  s.box.length = {edge, edge, edge};
  const double to_unit = 1.0 / std::cbrt(volume_fraction);
  for (std::size_t k = 0; k < r.size(); ++k)
    for (long q = 0; q < count[k]; ++q) {
      s.points.push_back({rng.uniform(0, edge), rng.uniform(0, edge), rng.uniform(0, edge)});
      s.unit_radius.push_back(r[k] * to_unit);
      s.klass.push_back(static_cast<int>(k));
    }
  return s;
}

double min_contact_ratio(const Packing& packing) {
  std::vector<Vec3> position = packing.position;
  NeighborList list(0.0);
  list.build(packing.box, position, packing.radius);
  double ratio = 1.0;
  for (int i = 0; i < static_cast<int>(packing.size()); ++i) {
    for (int p = list.first(i); p < list.first(i + 1); ++p) {
      const int j = list.partner()[p];
      const Vec3 d = position[j] + list.image_offset(list.image()[p]) - position[i];
      ratio = std::min(ratio, norm(d) / (packing.radius[i] + packing.radius[j]));
    }
  }
  return ratio;
}

}  // namespace packlab::generate
