#include "packlab/analyze/pore_size.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "packlab/core/error.hpp"

namespace packlab::analyze {

namespace {

// SplitMix64 (Steele, Lea & Flood 2014): the per-point streams.
std::uint64_t splitmix(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double unit_double(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

}  // namespace

PoreDefinition pore_definition_from_name(const std::string& name) {
  if (name == "pore_space") return PoreDefinition::pore_space;
  if (name == "all_points") return PoreDefinition::all_points;
  fail_input("pore_definition = " + name + ": must be pore_space or all_points");
}

std::string pore_definition_name(PoreDefinition definition) {
  return definition == PoreDefinition::pore_space ? "pore_space" : "all_points";
}

long points_for_band(double band, double confidence) {
  require(band > 0.0 && band < 0.5, "band", band, "in (0, 0.5)");
  require(confidence > 0.0 && confidence < 1.0, "confidence", confidence, "in (0, 1)");
  return static_cast<long>(std::ceil(std::log(2.0 / (1.0 - confidence)) / (2.0 * band * band)));
}

double band_for_points(long n, double confidence) {
  if (n <= 0) return 1.0;
  return std::sqrt(std::log(2.0 / (1.0 - confidence)) / (2.0 * static_cast<double>(n)));
}

// ---------------------------------------------------------------- SurfaceDistance

SurfaceDistance::SurfaceDistance(const Packing& packing) {
  packing.validate();
  const Box& box = packing.box;
  const std::size_t n = packing.size();
  if (n == 0) fail_input("pore size: the packing has no particles");
  periodic_ = box.periodic;
  for (double r : packing.radius) r_max_ = std::max(r_max_, r);
  // Region: the box along periodic axes; along open axes the box and every sphere.
  for (int a = 0; a < 3; ++a) {
    double lo = box.lo[a], hi = box.lo[a] + box.length[a];
    if (!periodic_[a])
      for (std::size_t i = 0; i < n; ++i) {
        lo = std::min(lo, packing.position[i][a] - packing.radius[i]);
        hi = std::max(hi, packing.position[i][a] + packing.radius[i]);
      }
    lo_[a] = lo;
    length_[a] = std::max(hi - lo, std::numeric_limits<double>::min());
  }
  // About one particle per cell: a nearest-surface query then visits a few dozen particles.
  const double volume = length_.x * length_.y * length_.z;
  const double h = std::cbrt(volume / static_cast<double>(n));
  for (int a = 0; a < 3; ++a) cells_[a] = std::clamp(static_cast<int>(length_[a] / h), 1, 1 << 10);
  while (static_cast<double>(cells_[0]) * cells_[1] * cells_[2] > 2.0 * static_cast<double>(n) + 64.0)
    for (int a = 0; a < 3; ++a) cells_[a] = std::max(1, cells_[a] / 2);
  h_min_ = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    cell_size_[a] = length_[a] / cells_[a];
    h_min_ = std::min(h_min_, cell_size_[a]);
  }
  const int total = cells_[0] * cells_[1] * cells_[2];
  std::vector<int> cell_of(n);
  cell_start_.assign(total + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = box.wrap(packing.position[i]);
    int c[3];
    for (int a = 0; a < 3; ++a)
      c[a] = std::clamp(static_cast<int>(std::floor((p[a] - lo_[a]) / cell_size_[a])), 0, cells_[a] - 1);
    cell_of[i] = c[0] + cells_[0] * (c[1] + cells_[1] * c[2]);
    ++cell_start_[cell_of[i] + 1];
  }
  for (int c = 0; c < total; ++c) cell_start_[c + 1] += cell_start_[c];
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  x_.resize(n);
  y_.resize(n);
  z_.resize(n);
  r_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = box.wrap(packing.position[i]);
    const int k = fill[cell_of[i]]++;
    x_[k] = p.x;
    y_[k] = p.y;
    z_[k] = p.z;
    r_[k] = packing.radius[i];
  }
}

double SurfaceDistance::operator()(const Vec3& point) const {
  int c[3];
  Vec3 p = point;
  for (int a = 0; a < 3; ++a) {
    if (periodic_[a]) p[a] -= length_[a] * std::floor((p[a] - lo_[a]) / length_[a]);
    c[a] = std::clamp(static_cast<int>(std::floor((p[a] - lo_[a]) / cell_size_[a])), 0, cells_[a] - 1);
  }
  double best = std::numeric_limits<double>::infinity();
  auto visit = [&](int dx, int dy, int dz) {
    const int d[3] = {dx, dy, dz};
    int idx[3];
    Vec3 shift;
    for (int a = 0; a < 3; ++a) {
      int m = c[a] + d[a];
      if (m < 0 || m >= cells_[a]) {
        if (!periodic_[a]) return false;
        const int wraps = static_cast<int>(std::floor(static_cast<double>(m) / cells_[a]));
        m -= wraps * cells_[a];
        shift[a] = wraps * length_[a];
      }
      idx[a] = m;
    }
    const int cell = idx[0] + cells_[0] * (idx[1] + cells_[1] * idx[2]);
    const double px = p.x - shift.x, py = p.y - shift.y, pz = p.z - shift.z;
    for (int k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
      const double ex = x_[k] - px, ey = y_[k] - py, ez = z_[k] - pz;
      const double d2 = ex * ex + ey * ey + ez * ez;
      const double rk = r_[k];
      if (d2 <= rk * rk) {
        best = 0.0;
        return true;
      }
      // sqrt only when this sphere can beat the best so far.
      const double reach = best + rk;
      if (d2 < reach * reach) best = std::sqrt(d2) - rk;
    }
    return false;
  };
  const int max_cells = std::max({cells_[0], cells_[1], cells_[2]});
  for (int k = 0;; ++k) {
    // Shell k: cells at Chebyshev distance exactly k from the point's cell.
    for (int dz = -k; dz <= k; ++dz)
      for (int dy = -k; dy <= k; ++dy) {
        const bool face = std::abs(dz) == k || std::abs(dy) == k;
        for (int dx = -k; dx <= k; dx += (face ? 1 : 2 * k)) {
          if (visit(dx, dy, dz)) return 0.0;
          if (k == 0) break;
        }
      }
    // Any cell of shell k+1 lies at least k * h_min from the point.
    if (best <= k * h_min_ - r_max_) return best;
    // Open box fully searched (no periodic axis to wrap around).
    if (!periodic_[0] && !periodic_[1] && !periodic_[2] && k >= max_cells) return best;
  }
}

// ---------------------------------------------------------------- PoreSize

PoreSize::PoreSize(PoreSizeParams params) : params_(params) {
  require(params.points >= 0, "points", static_cast<double>(params.points), "0 (automatic) or positive");
  require(params.threads >= 0, "threads", params.threads, "0 (all cores) or positive");
  require(params.confidence > 0.0 && params.confidence < 1.0, "confidence", params.confidence, "in (0, 1)");
  target_ = params.points > 0 ? params.points : points_for_band(params.band, params.confidence);
}

void PoreSize::compute(const Packing& packing, Random& rng, bool reset) {
  if (reset) {
    frames_.clear();
    pooled_ = Frame{};
  }
  const SurfaceDistance distance(packing);
  const Box& box = packing.box;
  const std::size_t n = packing.size();
  double mean_radius = 0.0;
  for (double r : packing.radius) mean_radius += r;
  mean_radius /= static_cast<double>(n);
  const double margin = params_.wall_margin < 0.0 ? 2.0 * mean_radius : params_.wall_margin;
  Vec3 lo = box.lo, extent = box.length;
  for (int a = 0; a < 3; ++a) {
    if (box.periodic[a]) continue;
    if (2.0 * margin >= box.length[a])
      fail_input(fmt::format("wall_margin = {:g}: must be less than half the box edge along {} ({:g}) for an open axis",
                             margin, "xyz"[a], box.length[a]));
    lo[a] += margin;
    extent[a] -= 2.0 * margin;
  }

  const std::uint64_t key = rng.next();
  const bool pore_space = params_.definition == PoreDefinition::pore_space;
  const int threads = params_.threads > 0 ? params_.threads : omp_get_max_threads();
  // Chunks of points in index order; each point's value depends only on (key, index), so
  // stopping after the chunk that reaches the target is independent of the thread count.
  const long chunk = 1L << 14;
  const long max_drawn = 200 * std::max(target_, chunk);
  Frame frame;
  frame.mean_radius = mean_radius;
  std::vector<double> value(chunk);
  long counted = 0;
  while (counted < target_) {
    if (frame.drawn >= max_drawn)
      fail_input(
          fmt::format("pore size: only {} of {} test points fell outside the particles: the packing leaves "
                      "(almost) no pore space to sample",
                      frame.outside, frame.drawn));
    const long base = frame.drawn;
#pragma omp parallel for num_threads(threads) schedule(static)
    for (long k = 0; k < chunk; ++k) {
      std::uint64_t state = key ^ (static_cast<std::uint64_t>(base + k) * 0xD1B54A32D192ED03ULL);
      (void)splitmix(state);
      Vec3 x;
      for (int a = 0; a < 3; ++a) x[a] = lo[a] + extent[a] * unit_double(splitmix(state));
      value[k] = distance(x);
    }
    for (long k = 0; k < chunk && counted < target_; ++k) {
      ++frame.drawn;
      if (value[k] > 0.0) ++frame.outside;
      if (value[k] > 0.0 || !pore_space) {
        frame.distances.push_back(value[k]);
        ++counted;
      }
    }
  }
  std::sort(frame.distances.begin(), frame.distances.end());
  // Pooled: merge, and weight every frame equally (equal counted points per frame).
  std::vector<double> merged(pooled_.distances.size() + frame.distances.size());
  std::merge(pooled_.distances.begin(), pooled_.distances.end(), frame.distances.begin(), frame.distances.end(),
             merged.begin());
  pooled_.distances = std::move(merged);
  pooled_.drawn += frame.drawn;
  pooled_.outside += frame.outside;
  pooled_.mean_radius = (pooled_.mean_radius * static_cast<double>(frames_.size()) + mean_radius) /
                        static_cast<double>(frames_.size() + 1);
  frames_.push_back(std::move(frame));
}

void PoreSize::require_computed() const {
  if (frames_.empty()) throw std::logic_error("PoreSize: compute() must be called before reading results");
}

const std::vector<double>& PoreSize::distances(int frame) const {
  require_computed();
  if (frame < 0) return pooled_.distances;
  if (frame >= static_cast<int>(frames_.size())) throw std::out_of_range("PoreSize: frame index");
  return frames_[frame].distances;
}

double PoreSize::probability(double r, int frame) const {
  const auto& d = distances(frame);
  if (d.empty()) return 0.0;
  // Fraction strictly greater than r.
  const auto above = d.end() - std::upper_bound(d.begin(), d.end(), r);
  return static_cast<double>(above) / static_cast<double>(d.size());
}

PoreSize::Curve PoreSize::curve(int points, int frame) const {
  require(points >= 2, "curve points", points, "at least 2");
  const auto& d = distances(frame);
  const double r_max = d.empty() ? 0.0 : d.back();
  const double n = static_cast<double>(d.size());
  const double eps = band(frame);
  Curve c;
  for (int k = 0; k < points; ++k) {
    const double r = r_max * k / (points - 1);
    const double p = probability(r, frame);
    c.r.push_back(r);
    c.probability.push_back(p);
    c.std_error.push_back(n > 0 ? std::sqrt(p * (1.0 - p) / n) : 0.0);
    c.band_low.push_back(std::max(0.0, p - eps));
    c.band_high.push_back(std::min(1.0, p + eps));
  }
  return c;
}

int PoreSize::frames() const { return static_cast<int>(frames_.size()); }

long PoreSize::counted_points(int frame) const { return static_cast<long>(distances(frame).size()); }

long PoreSize::drawn_points(int frame) const {
  require_computed();
  return frame < 0 ? pooled_.drawn : frames_.at(frame).drawn;
}

double PoreSize::porosity(int frame) const {
  require_computed();
  const Frame& f = frame < 0 ? pooled_ : frames_.at(frame);
  return static_cast<double>(f.outside) / static_cast<double>(f.drawn);
}

double PoreSize::porosity_std_error(int frame) const {
  const double p = porosity(frame);
  return std::sqrt(p * (1.0 - p) / static_cast<double>(drawn_points(frame)));
}

double PoreSize::band(int frame) const { return band_for_points(counted_points(frame), params_.confidence); }

double PoreSize::mean_radius(int frame) const {
  require_computed();
  return frame < 0 ? pooled_.mean_radius : frames_.at(frame).mean_radius;
}

// ---------------------------------------------------------------- DOH fit

DohFit fit_degree_of_heterogeneity(const PoreSize& pores, const DohFitOptions& options, int frame) {
  if (pores.params().definition != PoreDefinition::pore_space)
    fail_input("pore_definition = all_points: the degree-of-heterogeneity fit (eq. 6) needs pore_space");
  require(options.r0 >= 0.0, "r0", options.r0, "0 (mean radius) or positive [m]");
  require(options.p_min > 0.0 && options.p_min < 0.5, "fit_p_min", options.p_min, "in (0, 0.5)");
  require(options.grid >= 4, "fit_grid", options.grid, "at least 4");
  require(options.x_min >= 0.0, "fit_x_min", options.x_min, "non-negative");
  DohFit out;
  out.r0 = options.r0 > 0.0 ? options.r0 : pores.mean_radius(frame);
  const auto& d = pores.distances(frame);
  out.x_min = options.x_min;
  if (options.x_max > 0.0) {
    out.x_max = options.x_max;
  } else {
    // The r at which P(r_P > r) falls to p_min: the (1 - p_min) quantile of the distances.
    const auto k = static_cast<std::size_t>(std::floor((1.0 - options.p_min) * static_cast<double>(d.size())));
    out.x_max = d[std::min(k, d.size() - 1)] / out.r0;
  }
  if (!(out.x_max > out.x_min))
    fail_input(fmt::format("fit range = [{:g}, {:g}] r0: must have fit_x_max > fit_x_min", out.x_min, out.x_max));
  std::vector<double> x(options.grid), p(options.grid);
  for (int k = 0; k < options.grid; ++k) {
    x[k] = out.x_min + (out.x_max - out.x_min) * k / (options.grid - 1);
    p[k] = pores.probability(x[k] * out.r0, frame);
  }
  // Sampling covariance of the empirical survival function S at the grid points:
  // Cov(S(x), S(y)) = (S(max(x, y)) - S(x) S(y)) / n, used in the sandwich covariance of a, b.
  const double n = static_cast<double>(d.size());
  std::vector<std::vector<double>> sigma(options.grid, std::vector<double>(options.grid));
  for (int i = 0; i < options.grid; ++i)
    for (int k = 0; k < options.grid; ++k) sigma[i][k] = (p[std::max(i, k)] - p[i] * p[k]) / n;
  out.fit = fit_pore_erf(x, p, &sigma);
  return out;
}

}  // namespace packlab::analyze
