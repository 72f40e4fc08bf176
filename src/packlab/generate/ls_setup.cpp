// Lubachevsky–Stillinger growth: set-up (validation, classes, initial velocities), the cell
// grids rebuilt every block, the packing out, and the random start. The event loop is ls.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/memory.hpp"
#include "packlab/generate/ls.hpp"
#include "packlab/generate/overlap_check.hpp"

namespace packlab::generate {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double cell_margin = 1e-9;  // relative slack between the largest contact distance and a cell edge

}  // namespace

// ---------------------------------------------------------------------------------------------
// Set-up

LsSimulation::LsSimulation(const Packing& start, const LsParams& params, Random& rng) : params_(params) {
  params_.validate();
  start.validate();
  for (int a = 0; a < 3; ++a)
    if (!start.box.periodic[a])
      fail_input(
          fmt::format("box periodic along {} = false: Lubachevsky-Stillinger growth needs a box periodic "
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
      for (std::size_t i = 0; i < body_.size(); ++i) body_[i].v = start.velocity[body_[i].id];
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
      fail_input(
          fmt::format("box periodic along {} = false: Lubachevsky-Stillinger growth needs a box periodic "
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
  if (class_rho_.size() > max_classes)
    fail_input(fmt::format("distinct radii = {}: Lubachevsky-Stillinger growth supports at most {} size classes",
                           class_rho_.size(), max_classes));
  nclass_ = static_cast<int>(class_rho_.size());
  body_.resize(n);
  size_work_arrays();
  double volume = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    Body& b = body_[i];
    b.x = box_.wrap(points[i] - origin_);
    b.t = 0.0;
    int k = 0;
    while (k + 1 < nclass_ && unit_radius[i] < class_rho_[k] * (1.0 - 1e-12)) ++k;
    b.stamp = static_cast<std::uint32_t>(k);  // no collision yet
    b.id = static_cast<int>(i);
    const double rho = class_rho_[k];
    volume += 4.0 / 3.0 * std::numbers::pi * rho * rho * rho;
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
    fail_input(
        fmt::format("box edge = {:g} m is less than two largest diameters ({:g} m) at volume fraction {:g}; "
                    "use more particles",
                    l_min, 4.0 * class_rho_[0] * s_final, phi_final));
  status_ = LsStatus{};
  status_.scale = s0_;
  status_.volume_fraction = phi1_ * s0_ * s0_ * s0_;
}

void LsSimulation::size_work_arrays() {
  const std::size_t n = body_.size();
  ev_.resize(n);
  next_.resize(n);
}

namespace {
// The layout of the saved state: 2 since LsParams holds neighbor_list_limit (2026-12-02). The
// first layout began with the growth rate, whose low four bytes are not 2 for any rate in use,
// so an older checkpoint is refused with one message instead of being read shifted.
constexpr std::uint32_t ls_state_layout = 2;
}  // namespace

void LsSimulation::save_state(std::ostream& out) const {
  binary::write(out, ls_state_layout);
  binary::write(out, params_);
  binary::write(out, box_.lo);
  binary::write(out, box_.length);
  binary::write(out, origin_);
  binary::write_vector(out, class_rho_);
  binary::write(out, phi1_);
  binary::write(out, v_thermal_);
  binary::write(out, s0_);
  binary::write(out, skin_rel_);
  // The first layout (a particle with its radius, classes and counters beside).
  const std::size_t n = body_.size();
  std::vector<SavedBody> saved(n);
  std::vector<int> cls(n);
  std::vector<int> id(n);
  std::vector<std::uint32_t> count(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Body& b = body_[i];
    saved[i] = SavedBody{b.x, b.t, b.v, rho_of(b)};
    cls[i] = class_of(b);
    id[i] = b.id;
    count[i] = b.stamp >> class_bits;
  }
  binary::write_vector(out, saved);
  binary::write_vector(out, cls);
  binary::write_vector(out, id);
  binary::write_vector(out, count);
  binary::write(out, status_);
  binary::write(out, static_cast<std::uint8_t>(stopped_));
}

LsSimulation LsSimulation::load_state(std::istream& in) {
  LsSimulation sim;
  std::uint8_t stopped = 0;
  std::uint32_t layout = 0;
  binary::read(in, layout, "LS state layout");
  if (layout != ls_state_layout)
    fail_input("checkpoint is from an older packlab (its Lubachevsky-Stillinger state has another layout); "
               "start the run again");
  binary::read(in, sim.params_, "LS parameters");
  binary::read(in, sim.box_.lo, "box");
  binary::read(in, sim.box_.length, "box");
  binary::read(in, sim.origin_, "box origin");
  binary::read_vector(in, sim.class_rho_, "size classes", max_classes);
  binary::read(in, sim.phi1_, "volume fraction at s = 1");
  binary::read(in, sim.v_thermal_, "thermal speed");
  binary::read(in, sim.s0_, "scale");
  binary::read(in, sim.skin_rel_, "skin");
  std::vector<SavedBody> saved;
  std::vector<int> cls, id;
  std::vector<std::uint32_t> count;
  binary::read_vector(in, saved, "particles");
  binary::read_vector(in, cls, "classes");
  binary::read_vector(in, id, "particle ids");
  binary::read_vector(in, count, "collision counters");
  binary::read(in, sim.status_, "status");
  binary::read(in, stopped, "stop flag");
  sim.params_.validate();
  sim.box_.periodic = {true, true, true};
  sim.nclass_ = static_cast<int>(sim.class_rho_.size());
  const std::size_t n = saved.size();
  bool ok = n >= 2 && sim.nclass_ >= 1 && cls.size() == n && id.size() == n && count.size() == n;
  for (std::size_t i = 0; ok && i < n; ++i)
    ok = cls[i] >= 0 && cls[i] < sim.nclass_ && id[i] >= 0 && static_cast<std::size_t>(id[i]) < n &&
         saved[i].rho == sim.class_rho_[static_cast<std::size_t>(cls[i])];
  if (!ok) fail_input("checkpoint is damaged: Lubachevsky-Stillinger state out of range");
  sim.body_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    sim.body_[i] =
        Body{saved[i].x, saved[i].t, saved[i].v, (count[i] << class_bits) | static_cast<std::uint32_t>(cls[i]), id[i]};
  sim.stopped_ = stopped != 0;
  sim.size_work_arrays();
  return sim;
}

std::size_t LsSimulation::memory_bytes() const {
  std::size_t b = heap_bytes(class_rho_) + heap_bytes(reach_) + heap_bytes(body_) + heap_bytes(ev_) +
                  heap_bytes(next_) + heap_bytes(center_) + heap_bytes(bound_) + heap_bytes(skin_) +
                  heap_bytes(bound_cap_) + heap_bytes(list_cap_) + heap_bytes(list_base_) + heap_bytes(list_fill_) +
                  list_.size() * sizeof(std::uint32_t) + heap_bytes(hkey_) + heap_bytes(hid_) + heap_bytes(hpos_);
  for (const Grid& g : grid_) b += heap_bytes(g.head);
  return b;
}

double LsSimulation::mean_neighbors() const {
  double sum = 0.0;
  for (const std::uint16_t fill : list_fill_) sum += fill;
  return body_.empty() ? 0.0 : sum / static_cast<double>(body_.size());
}

void LsSimulation::note_memory(std::size_t temporary_bytes) {
  peak_bytes_ = std::max(peak_bytes_, memory_bytes() + temporary_bytes);
}

void LsSimulation::set_params(const LsParams& params) {
  params.validate();
  params_ = params;
  stopped_ = false;  // new criteria
}

void LsSimulation::set_positions(const std::vector<Vec3>& position) {
  if (position.size() != body_.size()) throw std::logic_error("LsSimulation::set_positions: wrong particle count");
  for (std::size_t i = 0; i < body_.size(); ++i) {
    body_[i].x = box_.wrap(position[body_[i].id] - origin_);
    body_[i].t = 0.0;
  }
}

// ---------------------------------------------------------------------------------------------
// Cells of bounding-sphere centres, one grid per class, rebuilt every block.

void LsSimulation::build_grids() {
  const double g = params_.growth_rate;
  const double s_want = g > 0.0 ? s0_ * 1.02 : s0_;
  std::vector<long> per_class(nclass_, 0);
  for (const Body& b : body_) ++per_class[class_of(b)];
  grid_.resize(nclass_);
  skin_.assign(nclass_, 0.0);
  bound_cap_.assign(nclass_, 0.0);
  // Skins relative to the current diameter, at least that of s = 0.2 (growth from points).
  const double l_min0 = std::min({box_.length.x, box_.length.y, box_.length.z});
  // Keep 2 x (largest bounding radius) within a quarter box.
  skin_rel_ = std::min(
      skin_rel_, std::max(min_skin_rel, (0.2 * l_min0 - class_rho_[0] * s_want) / (2.0 * class_rho_[0] * skin_scale(s0_))));
  // The list-length limit. Class k's bounding radius is rho_k (s + 2 skin_rel s_ref) = rho_k beta,
  // so in an ideal gas a sphere of class k has sum_m n_m (4/3) pi (rho_k + rho_m)^3 beta^3
  // neighbours (n_m: number density of class m); the mean over the spheres is C beta^3, and
  // beta <= cbrt(limit / C) bounds the skin. Denser states hold more neighbours than the gas
  // (the contact shell), and the per-block adaptation below keeps their lists short.
  if (params_.neighbor_list_limit > 0.0) {
    const double volume = box_.length.x * box_.length.y * box_.length.z;
    double c = 0.0;
    for (int k = 0; k < nclass_; ++k)
      for (int m = 0; m < nclass_; ++m) {
        const double sum = class_rho_[k] + class_rho_[m];
        c += static_cast<double>(per_class[k]) * static_cast<double>(per_class[m]) * sum * sum * sum;
      }
    c *= 4.0 / 3.0 * std::numbers::pi / (static_cast<double>(body_.size()) * volume);
    const double beta_max = std::cbrt(params_.neighbor_list_limit / c);
    skin_rel_ = std::min(skin_rel_, std::max(min_skin_rel, (beta_max - s_want) / (2.0 * skin_scale(s0_))));
  }
  for (int k = 0; k < nclass_; ++k) skin_[k] = skin_rel_ * 2.0 * class_rho_[k] * skin_scale(s0_);
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
    for (int m = 0; m < nclass_; ++m) reach_[k * nclass_ + m] = (bound_cap_[k] + bound_cap_[m]) * (1.0 + cell_margin);
  // Fill: members linked from each cell's head, in ascending order of index.
  for (int k = 0; k < nclass_; ++k) {
    Grid& gr = grid_[k];
    gr.head.assign(static_cast<std::size_t>(gr.n[0]) * gr.n[1] * gr.n[2], -1);
  }
  const std::size_t n = body_.size();
  center_.resize(n);
  for (std::size_t i = 0; i < n; ++i) center_[i] = body_[i].x;  // wrapped by sync_all
  for (int i = static_cast<int>(n) - 1; i >= 0; --i) insert(i);
  // Block end: the target or the largest scale these cells allow.
  t_target_ = inf;
  const double phi_t = params_.target_volume_fraction;
  if (phi_t > 0.0 && g > 0.0) t_target_ = (std::cbrt(phi_t / phi1_) - s0_) / g;
  const double t_cap = g > 0.0 ? (s_cap - s0_) / g : inf;
  target_in_block_ = t_target_ <= t_cap;
  t_end_ = std::min(t_target_, t_cap);
}

// ---------------------------------------------------------------------------------------------
// Result and start

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
    const int o = b.id;
    p.position[o] = box.wrap(b.x + b.v * (0.0 - b.t) + origin_);
    p.radius[o] = rho_of(b) * s0_;
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

LsStart make_ls_start(long particles, const SizeClasses& classes, double radius, double volume_fraction, Random& rng) {
  classes.validate();
  require(particles >= 2 && particles <= 100'000'000, "particles", static_cast<double>(particles), "in [2, 1e8]");
  // The process at its peak: the event-driven state (positions, velocities, event calendar,
  // cells, neighbour lists; ~200 B) with the start points and the packing out and its check,
  // measured at 390 B per sphere (bench_ls 1000000 3 0.6, peak_rss_per_particle).
  require_memory("particles", static_cast<double>(particles), static_cast<double>(particles), 400.0);
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

}  // namespace packlab::generate
