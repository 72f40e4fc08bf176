#include "packlab/analyze/rdf.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "packlab/core/error.hpp"

namespace packlab::analyze {

namespace {

constexpr double pi = std::numbers::pi;

// Fraction of the circle of radius rho (centre at the origin) inside [-a1, b1] x [-a2, b2]
// (distances >= 0, +inf for no bound). Excluded arcs are centred at 0, pi/2, pi, 3pi/2 with
// half-widths <= pi/2, so only neighbouring arcs can overlap: inclusion-exclusion is exact.
double circle_fraction(double rho, double a1, double b1, double a2, double b2) {
  if (rho <= 0.0) return 1.0;
  auto half = [rho](double d) { return d >= rho ? 0.0 : std::acos(d / rho); };
  const double h[4] = {half(b1), half(b2), half(a1), half(a2)};  // at 0, pi/2, pi, 3pi/2
  double excluded = 2.0 * (h[0] + h[1] + h[2] + h[3]);
  for (int q = 0; q < 4; ++q) excluded -= std::max(0.0, h[q] + h[(q + 1) % 4] - pi / 2);
  return std::clamp(1.0 - excluded / (2.0 * pi), 0.0, 1.0);
}

// 16-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr std::array<double, 8> gl_x{0.0950125098376374, 0.2816035507792589, 0.4580167776572274,
                                     0.6178762444026438, 0.7554044083550030, 0.8656312023878318,
                                     0.9445750230732326, 0.9894009349916499};
constexpr std::array<double, 8> gl_w{0.1894506104550685, 0.1826034150449236, 0.1691565193950025,
                                     0.1495959888165767, 0.1246289712555339, 0.0951585116824928,
                                     0.0622535239386479, 0.0271524594117541};

}  // namespace

double sphere_fraction_in_box(const Box& box, const Vec3& p, double r) {
  constexpr double none = std::numeric_limits<double>::infinity();
  double lo[3], hi[3];
  bool cut = false;
  for (int a = 0; a < 3; ++a) {
    lo[a] = box.periodic[a] ? none : std::max(0.0, p[a] - box.lo[a]);
    hi[a] = box.periodic[a] ? none : std::max(0.0, box.lo[a] + box.length[a] - p[a]);
    cut = cut || lo[a] < r || hi[a] < r;
  }
  if (!cut) return 1.0;
  // Archimedes: z of a uniform point on the sphere is uniform on [-r, r]; integrate the circle
  // fraction over z in pieces split where the integrand has kinks.
  std::vector<double> breaks{std::max(-r, -lo[2]), std::min(r, hi[2])};
  if (breaks[1] <= breaks[0]) return 0.0;
  for (double d : {lo[0], hi[0], lo[1], hi[1]})
    if (d < r) {
      const double z = std::sqrt(r * r - d * d);
      for (double zz : {-z, z})
        if (zz > breaks[0] && zz < breaks[1]) breaks.push_back(zz);
    }
  std::sort(breaks.begin(), breaks.end());
  double sum = 0.0;
  for (std::size_t q = 0; q + 1 < breaks.size(); ++q) {
    // z = z0 + (z1 - z0)(1 - cos t)/2, t in [0, pi]: the square-root kinks at the ends of a
    // piece become smooth, so Gauss-Legendre converges fast.
    const double z0 = breaks[q], z1 = breaks[q + 1];
    for (std::size_t k = 0; k < gl_x.size(); ++k)
      for (double sgn : {-1.0, 1.0}) {
        const double t = 0.5 * pi * (1.0 + sgn * gl_x[k]);
        const double z = z0 + (z1 - z0) * 0.5 * (1.0 - std::cos(t));
        const double jac = (z1 - z0) * 0.5 * std::sin(t) * 0.5 * pi;
        const double rho = std::sqrt(std::max(0.0, r * r - z * z));
        sum += gl_w[k] * jac * circle_fraction(rho, lo[0], hi[0], lo[1], hi[1]);
      }
  }
  return sum / (2.0 * r);
}

EdgeCorrection edge_correction_from_name(const std::string& name) {
  if (name == "auto" || name == "automatic") return EdgeCorrection::automatic;
  if (name == "toroidal") return EdgeCorrection::toroidal;
  if (name == "ripley") return EdgeCorrection::ripley;
  if (name == "minus" || name == "minus_sampling" || name == "minus-sampling") return EdgeCorrection::minus_sampling;
  fail_input("edge correction = " + name + ": must be auto, toroidal, ripley or minus-sampling");
}

std::string edge_correction_name(EdgeCorrection e) {
  switch (e) {
    case EdgeCorrection::automatic: return "auto";
    case EdgeCorrection::toroidal: return "toroidal";
    case EdgeCorrection::ripley: return "ripley";
    case EdgeCorrection::minus_sampling: return "minus-sampling";
  }
  return "?";
}

void RdfParams::validate() const {
  require(dr > 0.0 && dr <= 1.0, "dr", dr, "in (0, 1] particle radii");
  require(r_max > dr && r_max <= 1000.0, "rmax", r_max, "in (dr, 1000] particle radii");
  require(r_max / dr <= 1e7, "rmax / dr", r_max / dr, "<= 1e7 bins");
  require(window_radius > 0.0 && window_radius <= 100.0, "window_radius", window_radius, "in (0, 100] radii");
  require(threads >= 0, "threads", threads, ">= 0");
}

Rdf::Rdf(const RdfParams& params) : params_(params) { params_.validate(); }

void Rdf::reset() {
  realizations_ = 0;
  class_radius_.clear();
  mean_count_.clear();
  dk_.clear();
  di_.clear();
  contact_dk_.clear();
  window_hist_.clear();
}

void Rdf::compute(const Packing& packing) {
  reset();
  accumulate(packing);
}

std::size_t Rdf::pair_index(int k, int m) const {
  const int c = static_cast<int>(class_radius_.size());
  if (k < 0 || m < 0) return static_cast<std::size_t>(c) * c;
  if (k >= c || m >= c) throw std::out_of_range("Rdf: class index out of range");
  return static_cast<std::size_t>(k) * c + m;
}

void Rdf::accumulate(const Packing& packing) {
  packing.validate();
  const std::size_t n = packing.size();
  if (n < 2) fail_input("particles = " + std::to_string(n) + ": the RDF needs at least 2");
  // Classes: distinct radii, largest first.
  std::vector<double> distinct = packing.radius;
  std::sort(distinct.begin(), distinct.end(), std::greater<>());
  std::vector<double> radii;
  for (double r : distinct)
    if (radii.empty() || r < radii.back() * (1.0 - 1e-9)) radii.push_back(r);
  if (radii.size() > 16)
    fail_input(fmt::format("distinct radii = {}: the RDF sorts particles into at most 16 size classes", radii.size()));
  const int nc = static_cast<int>(radii.size());
  std::vector<int> klass(n);
  std::vector<long> count(nc, 0);
  for (std::size_t i = 0; i < n; ++i) {
    int k = 0;
    while (k + 1 < nc && packing.radius[i] < radii[k] * (1.0 - 1e-9)) ++k;
    klass[i] = k;
    ++count[k];
  }
  const double a = radii[0];
  const double dr = params_.dr;
  const std::size_t bins = static_cast<std::size_t>(std::floor(params_.r_max / dr + 1e-9));
  if (realizations_ == 0) {
    class_radius_ = radii;
    mean_count_.assign(nc, 0.0);
    bins_ = bins;
    const std::size_t np = static_cast<std::size_t>(nc) * nc + 1;
    dk_.assign(np, std::vector<double>(bins + 1, 0.0));
    di_.assign(np, std::vector<double>(bins + 1, 0.0));
    contact_dk_.assign(np, 0.0);
    window_hist_.assign(nc + 1, {});
  } else if (nc != static_cast<int>(class_radius_.size())) {
    fail_input(fmt::format("size classes = {}: every realization must have the same number of size classes ({})", nc,
                           class_radius_.size()));
  }
  const Box& box = packing.box;
  EdgeCorrection edge = params_.edge;
  if (edge == EdgeCorrection::automatic)
    edge = box.periodic[0] && box.periodic[1] && box.periodic[2] ? EdgeCorrection::toroidal : EdgeCorrection::ripley;
  if (edge == EdgeCorrection::toroidal && !(box.periodic[0] && box.periodic[1] && box.periodic[2]))
    fail_input("edge correction = toroidal: the box must be periodic on every axis");
  // Pairs are counted up to the upper edge of the last bin.
  const double r_max = (static_cast<double>(bins) + 0.5) * dr * a;
  double window_max = 0.0;
  for (double r : radii) window_max = std::max(window_max, params_.window_radius * r);
  const double range = std::max(r_max, window_max);
  // Minus-sampling / windows: a centre is "inner" when farther than the range from open faces.
  auto inner = [&](const Vec3& p, double d) {
    for (int ax = 0; ax < 3; ++ax)
      if (!box.periodic[ax] && (p[ax] - box.lo[ax] < d || box.lo[ax] + box.length[ax] - p[ax] < d)) return false;
    return true;
  };
  // Cells of edge >= range / 2 (stencil of +-2 cells), images enumerated through unwrapped cells.
  int nx[3];
  double h[3];
  for (int ax = 0; ax < 3; ++ax) {
    nx[ax] = std::max(1, static_cast<int>(std::floor(box.length[ax] / (0.5 * range))));
    nx[ax] = std::min(nx[ax], 512);
    h[ax] = box.length[ax] / nx[ax];
  }
  std::vector<Vec3> pos(n);
  std::vector<int> cell_of(n), cell_start(static_cast<std::size_t>(nx[0]) * nx[1] * nx[2] + 1, 0), order(n);
  for (std::size_t i = 0; i < n; ++i) {
    pos[i] = box.wrap(packing.position[i]);
    int c[3];
    for (int ax = 0; ax < 3; ++ax)
      c[ax] = std::clamp(static_cast<int>(std::floor((pos[i][ax] - box.lo[ax]) / h[ax])), 0, nx[ax] - 1);
    cell_of[i] = c[0] + nx[0] * (c[1] + nx[1] * c[2]);
    ++cell_start[cell_of[i] + 1];
  }
  for (std::size_t c = 1; c < cell_start.size(); ++c) cell_start[c] += cell_start[c - 1];
  {
    std::vector<int> fill(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) order[fill[cell_of[i]]++] = static_cast<int>(i);
  }
  int reach[3];
  for (int ax = 0; ax < 3; ++ax) reach[ax] = static_cast<int>(std::ceil(range / h[ax]));
  const int np = nc * nc + 1;
  // Per centre i: weighted counts per (class of j, bin) and contact counts.
  const int threads = params_.threads > 0 ? params_.threads : omp_get_max_threads();
  std::vector<std::vector<double>> t_hist(threads, std::vector<double>(static_cast<std::size_t>(nc) * nc * (bins + 1), 0.0));
  std::vector<std::vector<double>> t_cnt(threads, std::vector<double>(static_cast<std::size_t>(nc) * nc * (bins + 1), 0.0));
  std::vector<std::vector<double>> t_contact(threads, std::vector<double>(static_cast<std::size_t>(nc) * nc, 0.0));
  std::vector<int> window_count(n, -1);
  std::vector<char> is_inner(n, 1);
  const bool minus = edge == EdgeCorrection::minus_sampling;
  const bool ripley = edge == EdgeCorrection::ripley;
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads)
  for (long li = 0; li < static_cast<long>(n); ++li) {
    const int tid = omp_get_thread_num();
    const auto i = static_cast<std::size_t>(li);
    const Vec3 pi_ = pos[i];
    const int ki = klass[i];
    const double window = params_.window_radius * radii[ki];
    const bool in_r = inner(pi_, r_max);
    const bool in_w = inner(pi_, window);
    is_inner[i] = in_r ? 1 : 0;
    int ci[3];
    for (int ax = 0; ax < 3; ++ax)
      ci[ax] = std::clamp(static_cast<int>(std::floor((pi_[ax] - box.lo[ax]) / h[ax])), 0, nx[ax] - 1);
    int wcount = 0;
    double* hist = t_hist[tid].data();
    double* cnt = t_cnt[tid].data();
    double* contact = t_contact[tid].data();
    for (int uz = ci[2] - reach[2]; uz <= ci[2] + reach[2]; ++uz) {
      int wz = uz, sz = 0;
      if (wz < 0 || wz >= nx[2]) {
        if (!box.periodic[2]) continue;
        sz = static_cast<int>(std::floor(static_cast<double>(uz) / nx[2]));
        wz = uz - sz * nx[2];
      }
      for (int uy = ci[1] - reach[1]; uy <= ci[1] + reach[1]; ++uy) {
        int wy = uy, sy = 0;
        if (wy < 0 || wy >= nx[1]) {
          if (!box.periodic[1]) continue;
          sy = static_cast<int>(std::floor(static_cast<double>(uy) / nx[1]));
          wy = uy - sy * nx[1];
        }
        for (int ux = ci[0] - reach[0]; ux <= ci[0] + reach[0]; ++ux) {
          int wx = ux, sx = 0;
          if (wx < 0 || wx >= nx[0]) {
            if (!box.periodic[0]) continue;
            sx = static_cast<int>(std::floor(static_cast<double>(ux) / nx[0]));
            wx = ux - sx * nx[0];
          }
          const Vec3 off{sx * box.length.x, sy * box.length.y, sz * box.length.z};
          const int cell = wx + nx[0] * (wy + nx[1] * wz);
          for (int q = cell_start[cell]; q < cell_start[cell + 1]; ++q) {
            const auto j = static_cast<std::size_t>(order[q]);
            if (j == i && sx == 0 && sy == 0 && sz == 0) continue;
            const Vec3 d = pos[j] + off - pi_;
            const double r2 = norm2(d);
            if (r2 >= range * range) continue;
            const double r = std::sqrt(r2);
            if (r < window) ++wcount;
            if (r >= r_max || (minus && !in_r)) continue;
            const int kj = klass[j];
            const double w = ripley ? 1.0 / sphere_fraction_in_box(box, pi_, r) : 1.0;
            const double rr = r / a;
            const auto bin = static_cast<std::size_t>(std::floor(rr / dr + 0.5));
            const std::size_t pair = static_cast<std::size_t>(ki) * nc + kj;
            if (bin >= 1 && bin <= bins) {
              hist[pair * (bins + 1) + bin] += w;
              cnt[pair * (bins + 1) + bin] += 1.0;
            }
            const double sigma = (radii[ki] + radii[kj]) / a;
            if (rr >= sigma * (1.0 - 1e-9) && rr < sigma + dr) contact[pair] += w;
          }
        }
      }
    }
    if (in_w) window_count[i] = wcount;
  }
  // Reduce in thread order (deterministic for a given thread count; counts are exact).
  const double volume = box.volume();
  std::vector<long> inner_count(nc, 0);
  for (std::size_t i = 0; i < n; ++i)
    if (!minus || is_inner[i]) ++inner_count[klass[i]];
  for (int k = 0; k < nc; ++k)
    if (minus && inner_count[k] == 0)
      fail_input(fmt::format("rmax = {:g}: no particle of class {} is farther than rmax from every open face; "
                             "use a smaller rmax or another edge correction",
                             params_.r_max, k));
  const double a3 = a * a * a;
  std::vector<double> pair_hist(static_cast<std::size_t>(nc) * nc * (bins + 1), 0.0), pair_cnt(pair_hist.size(), 0.0),
      pair_contact(static_cast<std::size_t>(nc) * nc, 0.0);
  for (int t = 0; t < threads; ++t) {
    for (std::size_t q = 0; q < pair_hist.size(); ++q) {
      pair_hist[q] += t_hist[t][q];
      pair_cnt[q] += t_cnt[t][q];
    }
    for (std::size_t q = 0; q < pair_contact.size(); ++q) pair_contact[q] += t_contact[t][q];
  }
  // K_km increments: V / (N_k N_m) sum, eqs. (2) and (5) with the intensity estimated by N/V (so
  // g tends to 1 - 1/N for a Poisson pattern of N points), in units of a^3; total likewise.
  long total_inner = 0;
  for (long c : inner_count) total_inner += c;
  const std::size_t total = static_cast<std::size_t>(np - 1);
  for (int k = 0; k < nc; ++k)
    for (int m = 0; m < nc; ++m) {
      const std::size_t p = static_cast<std::size_t>(k) * nc + m;
      const double others = static_cast<double>(count[m]);
      const double norm = others > 0 ? volume / (static_cast<double>(inner_count[k]) * others) / a3 : 0.0;
      for (std::size_t b = 1; b <= bins; ++b) {
        dk_[p][b] += pair_hist[p * (bins + 1) + b] * norm;
        di_[p][b] += pair_cnt[p * (bins + 1) + b] / static_cast<double>(inner_count[k]);
      }
      contact_dk_[p] += pair_contact[p] * norm;
    }
  const double norm_total = volume / (static_cast<double>(total_inner) * static_cast<double>(n)) / a3;
  for (std::size_t p = 0; p < total; ++p) {
    for (std::size_t b = 1; b <= bins; ++b) {
      dk_[total][b] += pair_hist[p * (bins + 1) + b] * norm_total;
      di_[total][b] += pair_cnt[p * (bins + 1) + b] / static_cast<double>(total_inner);
    }
    contact_dk_[total] += pair_contact[p] * norm_total;
  }
  // Windows.
  for (std::size_t i = 0; i < n; ++i) {
    const int c = window_count[i];
    if (c < 0) continue;
    for (auto* hist : {&window_hist_[klass[i]], &window_hist_[nc]}) {
      if (hist->size() <= static_cast<std::size_t>(c)) hist->resize(c + 1, 0);
      ++(*hist)[c];
    }
  }
  for (int k = 0; k < nc; ++k) mean_count_[k] += static_cast<double>(count[k]);
  ++realizations_;
}

void Rdf::add(const Rdf& other) {
  other.require_computed();
  if (realizations_ == 0) {
    *this = other;
    return;
  }
  if (other.class_radius_.size() != class_radius_.size() || other.bins_ != bins_ || other.params_.dr != params_.dr)
    fail_input("realizations differ in size classes or bins; they cannot be averaged");
  for (std::size_t p = 0; p < dk_.size(); ++p) {
    for (std::size_t b = 0; b <= bins_; ++b) {
      dk_[p][b] += other.dk_[p][b];
      di_[p][b] += other.di_[p][b];
    }
    contact_dk_[p] += other.contact_dk_[p];
  }
  for (std::size_t k = 0; k < window_hist_.size(); ++k) {
    if (window_hist_[k].size() < other.window_hist_[k].size()) window_hist_[k].resize(other.window_hist_[k].size(), 0);
    for (std::size_t c = 0; c < other.window_hist_[k].size(); ++c) window_hist_[k][c] += other.window_hist_[k][c];
  }
  for (std::size_t k = 0; k < mean_count_.size(); ++k) mean_count_[k] += other.mean_count_[k];
  realizations_ += other.realizations_;
}

void Rdf::require_computed() const {
  if (realizations_ == 0) throw std::logic_error("Rdf: compute() must be called before reading results");
}

int Rdf::realizations() const { return realizations_; }
int Rdf::classes() const {
  require_computed();
  return static_cast<int>(class_radius_.size());
}
const std::vector<double>& Rdf::class_radius() const {
  require_computed();
  return class_radius_;
}
double Rdf::reference_radius() const { return class_radius()[0]; }
std::size_t Rdf::bins() const {
  require_computed();
  return bins_;
}

std::vector<double> Rdf::reduced_r() const {
  require_computed();
  std::vector<double> r(bins_);
  for (std::size_t b = 1; b <= bins_; ++b) r[b - 1] = static_cast<double>(b) * params_.dr;
  return r;
}

std::vector<double> Rdf::k_function(int k, int m) const {
  require_computed();
  const auto& d = dk_[pair_index(k, m)];
  std::vector<double> out(bins_);
  double sum = 0.0;
  for (std::size_t b = 1; b <= bins_; ++b) {
    sum += d[b];
    out[b - 1] = sum / realizations_;
  }
  return out;
}

std::vector<double> Rdf::g(int k, int m) const {
  require_computed();
  const auto& d = dk_[pair_index(k, m)];
  std::vector<double> out(bins_);
  for (std::size_t b = 1; b <= bins_; ++b) {
    const double r = static_cast<double>(b) * params_.dr;
    out[b - 1] = d[b] / realizations_ / (4.0 * pi * r * r * params_.dr);
  }
  return out;
}

std::vector<double> Rdf::shell_count(int k, int m) const {
  require_computed();
  const auto& d = di_[pair_index(k, m)];
  std::vector<double> out(bins_);
  for (std::size_t b = 1; b <= bins_; ++b) out[b - 1] = d[b] / realizations_;
  return out;
}

double Rdf::contact_value(int k, int m) const {
  require_computed();
  double sigma;
  if (k < 0) {
    sigma = 2.0;  // all pairs: contact of the reference class
  } else {
    (void)pair_index(k, m);
    sigma = (class_radius_[k] + class_radius_[m]) / class_radius_[0];
  }
  return contact_dk_[pair_index(k, m)] / realizations_ / (4.0 * pi * sigma * sigma * params_.dr);
}

std::vector<double> Rdf::peaks(int k, int m, std::size_t count) const {
  const std::vector<double> gv = g(k, m);
  const double sigma = k < 0 ? 2.0 : (class_radius_[k] + class_radius_[m]) / class_radius_[0];
  const std::size_t n = gv.size();
  std::vector<double> smooth(n, 0.0);
  for (std::size_t b = 0; b < n; ++b) {
    double s = 0.0;
    int c = 0;
    for (long q = static_cast<long>(b) - 2; q <= static_cast<long>(b) + 2; ++q)
      if (q >= 0 && q < static_cast<long>(n)) {
        s += gv[q];
        ++c;
      }
    smooth[b] = s / c;
  }
  const long half = std::max(1L, static_cast<long>(std::lround(0.15 / params_.dr)));
  std::vector<double> out;
  for (std::size_t b = 0; b < n && out.size() < count; ++b) {
    const double r = static_cast<double>(b + 1) * params_.dr;
    if (r < sigma - 0.5 * params_.dr || smooth[b] <= 1.0) continue;
    bool is_max = true;
    for (long q = static_cast<long>(b) - half; q <= static_cast<long>(b) + half && is_max; ++q)
      if (q >= 0 && q < static_cast<long>(n) && q != static_cast<long>(b) && smooth[q] > smooth[b]) is_max = false;
    if (is_max && (out.empty() || r - out.back() > 0.15)) out.push_back(r);
  }
  return out;
}

std::vector<double> Rdf::window_histogram(int k) const {
  require_computed();
  const auto& h = window_hist_[k < 0 ? class_radius_.size() : static_cast<std::size_t>(k)];
  long total = 0;
  for (long c : h) total += c;
  std::vector<double> p(h.size(), 0.0);
  for (std::size_t c = 0; c < h.size(); ++c) p[c] = total > 0 ? static_cast<double>(h[c]) / static_cast<double>(total) : 0.0;
  return p;
}

long Rdf::windows(int k) const {
  require_computed();
  const auto& h = window_hist_[k < 0 ? class_radius_.size() : static_cast<std::size_t>(k)];
  long total = 0;
  for (long c : h) total += c;
  return total;
}

}  // namespace packlab::analyze
