#include "packlab/generate/shake.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/generate/overlap_check.hpp"
#include "packlab/io/options.hpp"

namespace packlab::generate {

void ShakeParams::validate() const {
  ShakeParams copy = *this;
  io::ConfigSchema declared("shake");
  io::add_shake_params(declared, copy);
  declared.validate();
  if (move_rule != "metropolis" && move_rule != "freest")
    fail_input("move_rule = " + move_rule + ": must be metropolis or freest");
  require(adapt_factor > 1.0 && adapt_factor <= 2.0, "adapt_factor", adapt_factor, "in (1, 2]");
  require(min_window > 0.0 && min_window <= window, "min_window", min_window, "in (0, window]");
  require(max_window >= window && max_window <= 1.0, "max_window", max_window, "in [window, 1]");
}

Shaker::Shaker(Packing& packing, const ShakeParams& params) : p_(packing), params_(params) {
  params_.validate();
  metropolis_ = params_.move_rule == "metropolis";
  p_.validate();
  const std::size_t n = p_.size();
  if (n < 2) fail_input("particles = " + std::to_string(n) + ": shaking needs at least 2");
  const double ratio = min_contact_ratio(p_);
  require(ratio >= 1.0 - 1e-9, "min contact ratio d/(r_i+r_j)", ratio,
          ">= 1: the packing has overlapping spheres (shaking needs a hard-sphere packing)");
  std::vector<double> distinct = p_.radius;
  std::sort(distinct.begin(), distinct.end(), std::greater<>());
  for (double r : distinct)
    if (class_radius_.empty() || r < class_radius_.back() * (1.0 - 1e-9)) class_radius_.push_back(r);
  klass_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    int k = 0;
    while (k + 1 < static_cast<int>(class_radius_.size()) && p_.radius[i] < class_radius_[k] * (1.0 - 1e-9)) ++k;
    klass_[i] = k;
  }
  stats_.window.assign(class_radius_.size(), params_.window);
  // Cells no smaller than the largest testing window, and no more cells than about two per
  // particle: SCRM shakes during growth, when the spheres are still small (a grid sized by their
  // radius alone took gigabytes after one LS block).
  const double a_max = class_radius_[0];
  const double range = (2.0 + (params_.adaptive ? params_.max_window : params_.window)) * a_max * (1.0 + 1e-9);
  const double sparse =
      std::cbrt(p_.box.length[0] * p_.box.length[1] * p_.box.length[2] / (2.0 * static_cast<double>(n)));
  for (int a = 0; a < 3; ++a) {
    if (p_.box.periodic[a] && p_.box.length[a] < 2.0 * range)
      fail_input(fmt::format("box edge along {} = {:g} m: shaking needs at least {:g} m (two testing windows)",
                             "xyz"[a], p_.box.length[a], 2.0 * range));
    n_[a] = std::clamp(static_cast<int>(std::floor(p_.box.length[a] / std::max(range, sparse))), 1, 1024);
    h_[a] = p_.box.length[a] / n_[a];
  }
  fill_cells();
}

void Shaker::fill_cells() {
  const std::size_t n = p_.size();
  cells_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2], {});
  cell_of_.resize(n);
  slot_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    p_.position[i] = p_.box.wrap(p_.position[i]);
    const int c = cell_index(p_.position[i]);
    cell_of_[i] = c;
    slot_[i] = static_cast<int>(cells_[c].size());
    cells_[c].push_back(static_cast<int>(i));
  }
}

void write_shake_stats(std::ostream& out, const ShakeStats& stats) {
  binary::write(out, stats.sweeps);
  binary::write(out, stats.visits);
  binary::write(out, stats.trials);
  binary::write(out, stats.moves);
  binary::write(out, stats.mean_step);
  binary::write(out, stats.seconds);
  binary::write_vector(out, stats.window);
}

ShakeStats read_shake_stats(std::istream& in) {
  ShakeStats stats;
  binary::read(in, stats.sweeps, "sweeps");
  binary::read(in, stats.visits, "visits");
  binary::read(in, stats.trials, "trials");
  binary::read(in, stats.moves, "moves");
  binary::read(in, stats.mean_step, "mean step");
  binary::read(in, stats.seconds, "seconds");
  binary::read_vector(in, stats.window, "windows");
  return stats;
}

void Shaker::save_state(std::ostream& out) const {
  binary::write(out, p_.box.lo);
  binary::write(out, p_.box.length);
  binary::write_vector(out, p_.radius);
  binary::write_vector(out, p_.position);
  write_shake_stats(out, stats_);
  binary::write(out, step_sum_);
}

void Shaker::load_state(std::istream& in) {
  Vec3 lo, length;
  std::vector<double> radius;
  std::vector<Vec3> position;
  binary::read(in, lo, "box");
  binary::read(in, length, "box");
  binary::read_vector(in, radius, "radii");
  if (lo != p_.box.lo || length != p_.box.length || radius != p_.radius)
    fail_input("the saved shaking is of another packing (box or radii differ from the input file)");
  binary::read_vector(in, position, "positions");
  ShakeStats stats = read_shake_stats(in);
  binary::read(in, step_sum_, "step sum");
  if (position.size() != p_.size() || stats.window.size() != stats_.window.size() || stats.sweeps < 0)
    fail_input("checkpoint is damaged: shaking state out of range");
  p_.position = std::move(position);
  stats_ = std::move(stats);
  fill_cells();
}

int Shaker::cell_index(const Vec3& p) const {
  int c[3];
  for (int a = 0; a < 3; ++a)
    c[a] = std::clamp(static_cast<int>(std::floor((p[a] - p_.box.lo[a]) / h_[a])), 0, n_[a] - 1);
  return c[0] + n_[0] * (c[1] + n_[1] * c[2]);
}

void Shaker::gather(int i, double range) const {
  near_.clear();
  const Vec3 xi = p_.position[i];
  int c[3];
  for (int a = 0; a < 3; ++a)
    c[a] = std::clamp(static_cast<int>(std::floor((xi[a] - p_.box.lo[a]) / h_[a])), 0, n_[a] - 1);
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int d[3] = {dx, dy, dz};
        int w[3];
        Vec3 off{};
        bool skip = false;
        for (int a = 0; a < 3; ++a) {
          int u = c[a] + d[a];
          if (u < 0 || u >= n_[a]) {
            if (!p_.box.periodic[a]) {
              skip = true;
              break;
            }
            const int s = u < 0 ? -1 : 1;
            u -= s * n_[a];
            off[a] = s * p_.box.length[a];
          }
          w[a] = u;
        }
        if (skip) continue;
        for (int j : cells_[w[0] + n_[0] * (w[1] + n_[1] * w[2])]) {
          if (j == i) continue;
          const Vec3 rel = p_.position[j] + off - xi;
          const double reach = range + p_.radius[j];
          if (norm2(rel) < reach * reach) near_.emplace_back(j, off);
        }
      }
}

double Shaker::free_distance(int i, const Vec3& u, double limit) const {
  gather(i, p_.radius[i] + limit);
  return free_distance_gathered(i, u, limit);
}

double Shaker::free_distance_gathered(int i, const Vec3& u, double limit) const {
  const Vec3 xi = p_.position[i];
  double best = limit;
  for (const auto& [j, off] : near_) {
    const Vec3 d = p_.position[j] + off - xi;
    const double sigma = p_.radius[i] + p_.radius[j];
    const double b = dot(u, d);
    if (b <= 0.0) continue;  // moving away (touching pairs may separate)
    const double c = norm2(d) - sigma * sigma;
    if (c <= 0.0) return 0.0;
    if (b * limit * 2.0 <= c) continue;  // the root c / (b + sqrt(b^2 - c)) >= c / (2b) exceeds the limit
    const double disc = b * b - c;
    if (disc < 0.0) continue;
    best = std::min(best, c / (b + std::sqrt(disc)));
  }
  // Open axes: the centre stays in the box.
  for (int a = 0; a < 3; ++a) {
    if (p_.box.periodic[a] || u[a] == 0.0) continue;
    const double wall = u[a] > 0.0 ? p_.box.lo[a] + p_.box.length[a] : p_.box.lo[a];
    best = std::min(best, std::max(0.0, (wall - xi[a]) / u[a]));
  }
  return best;
}

bool Shaker::overlaps_gathered(int i, const Vec3& x) const {
  for (int a = 0; a < 3; ++a)
    if (!p_.box.periodic[a] && (x[a] < p_.box.lo[a] || x[a] > p_.box.lo[a] + p_.box.length[a])) return true;
  for (const auto& [j, off] : near_) {
    const double sigma = p_.radius[i] + p_.radius[j];
    if (norm2(p_.position[j] + off - x) < sigma * sigma) return true;
  }
  return false;
}

void Shaker::move_to(int i, const Vec3& x_new, double step) {
  const Vec3 x = p_.box.wrap(x_new);
  p_.position[i] = x;
  const int c = cell_index(x);
  if (c != cell_of_[i]) {
    auto& old = cells_[cell_of_[i]];
    const int moved = old.back();
    old[slot_[i]] = moved;
    slot_[moved] = slot_[i];
    old.pop_back();
    slot_[i] = static_cast<int>(cells_[c].size());
    cells_[c].push_back(i);
    cell_of_[i] = c;
  }
  ++stats_.moves;
  step_sum_ += step;
  stats_.mean_step = step_sum_ / static_cast<double>(stats_.moves);
}

// scrm-bimodal-packs §3.2: "the selected particle center x_i is randomly moved to a new position
// x'_i uniformly distributed in the window w_s ... If the particle does not overlap with any other
// inclusions the shaking is accepted, otherwise the trial shaking is repeated until the number of
// attempted trial shakings exceed some limit N_sh."
void Shaker::visit_metropolis(int i, Random& rng) {
  ++stats_.visits;
  const int k = klass_[i];
  const double a = p_.radius[i];
  double& window = stats_.window[k];
  const double limit = window * a;
  gather(i, a + limit);
  const Vec3 xi = p_.position[i];
  for (int trial = 0; trial < params_.max_trials; ++trial) {
    ++stats_.trials;
    // Uniform in the ball: direction uniform, radius with density ~ r^2.
    const Vec3 u = rng.unit_vector();
    const double r = limit * std::cbrt(rng.uniform());
    const Vec3 x = xi + u * r;
    if (overlaps_gathered(i, x)) continue;
    // Adapting: a window whose first trial succeeds grows, one that needed more shrinks (an
    // acceptance of about one half per trial).
    if (params_.adaptive)
      window = trial == 0 ? std::min(params_.max_window, window * params_.adapt_factor)
                          : std::max(params_.min_window, window / params_.adapt_factor);
    move_to(i, x, r / a);
    return;
  }
  if (params_.adaptive) window = std::max(params_.min_window, window / params_.adapt_factor);
}

void Shaker::visit(int i, Random& rng) {
  if (metropolis_) {
    visit_metropolis(i, rng);
    return;
  }
  ++stats_.visits;
  const int k = klass_[i];
  const double a = p_.radius[i];
  double& window = stats_.window[k];
  const double limit = window * a;
  // When adapting, look beyond the window to know whether the free distance exceeded it.
  const double search = params_.adaptive ? 2.0 * limit : limit;
  gather(i, a + search);
  double best = -1.0;
  Vec3 best_u{};
  for (int trial = 0; trial < params_.max_trials; ++trial) {
    ++stats_.trials;
    const Vec3 u = rng.unit_vector();
    const double dt = free_distance_gathered(i, u, search);
    if (dt > best) {
      best = dt;
      best_u = u;
      if (best >= search) break;  // free over the whole window: no direction can do better
    }
  }
  if (params_.adaptive)
    window = best > limit ? std::min(params_.max_window, window * params_.adapt_factor)
                          : std::max(params_.min_window, window / params_.adapt_factor);
  const double amplitude_max = std::min(best, limit);
  if (amplitude_max <= 1e-12 * a) return;  // blocked in every trial direction
  const double amplitude = rng.uniform() * amplitude_max;
  move_to(i, p_.position[i] + best_u * amplitude, amplitude / a);
}

void Shaker::sweep(Random& rng) {
  const auto t0 = std::chrono::steady_clock::now();
  const int n = static_cast<int>(p_.size());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  for (int q = n - 1; q > 0; --q) std::swap(order[q], order[rng.below(static_cast<std::uint64_t>(q) + 1)]);
  for (int i : order) visit(i, rng);
  ++stats_.sweeps;
  stats_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void Shaker::sweeps(long m, Random& rng, const std::function<void(const ShakeStats&)>& on_sweep) {
  require(m >= 0, "sweeps", static_cast<double>(m), ">= 0");
  for (long s = 0; s < m; ++s) {
    sweep(rng);
    if (on_sweep) on_sweep(stats_);
  }
}

}  // namespace packlab::generate
