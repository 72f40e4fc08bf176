#include "packlab/generate/fba.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/memory.hpp"
#include "packlab/core/neighbor_list.hpp"
#include "packlab/io/options.hpp"

namespace packlab::generate {

void FbaParams::validate() const {
  FbaParams copy = *this;
  io::ConfigSchema declared("generate fba");
  io::add_fba_params(declared, copy);
  declared.validate();
  require(max_move > 0.0 && max_move <= 2.0, "max_move", max_move, "in (0, 2] target radii");
}

std::string fba_stop_name(FbaStop stop) {
  switch (stop) {
    case FbaStop::target_reached:
      return "target_reached";
    case FbaStop::max_iterations:
      return "max_iterations";
  }
  return "unknown";
}

std::vector<double> fba_class_radii(long count, const SizeClasses& classes, Random& rng) {
  require(count >= 1, "particles", static_cast<double>(count), ">= 1");
  const std::vector<long> per_class = classes.counts(count);
  std::vector<double> rho;
  rho.reserve(static_cast<std::size_t>(count));
  for (std::size_t k = 0; k < per_class.size(); ++k)
    for (long n = 0; n < per_class[k]; ++n) rho.push_back(0.5 * classes.sizes[k]);
  // Fisher–Yates with the one generator (std::shuffle's draws are implementation-defined).
  for (std::size_t i = rho.size(); i > 1; --i) std::swap(rho[i - 1], rho[rng.below(i)]);
  return rho;
}

long fba_count_for_volume(double volume, double porosity, double max_diameter, const SizeClasses& classes) {
  require(volume > 0.0 && std::isfinite(volume), "box volume", volume, "> 0 m^3");
  require(max_diameter > 0.0 && std::isfinite(max_diameter), "diameter", max_diameter, "> 0 m");
  require(porosity >= 0.0 && porosity < 1.0, "porosity", porosity, "in [0, 1)");
  const std::vector<double> x = classes.number_fractions();
  const double smax = *std::max_element(classes.sizes.begin(), classes.sizes.end());
  double mean_volume = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double d = classes.sizes[k] / smax * max_diameter;
    mean_volume += x[k] * std::numbers::pi / 6.0 * d * d * d;
  }
  const double n = std::round((1.0 - porosity) * volume / mean_volume);
  require(n <= 1e8, "particles", n, "<= 1e8 (box too large for this diameter)");
  return std::max(1L, static_cast<long>(n));
}

double brute_force_max_overlap(const Packing& p) {
  const Box& box = p.box;
  double worst = 0.0;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j)
      for (int sx = -1; sx <= 1; ++sx)
        for (int sy = -1; sy <= 1; ++sy)
          for (int sz = -1; sz <= 1; ++sz) {
            const std::array<int, 3> s{sx, sy, sz};
            bool ok = true;
            for (int a = 0; a < 3; ++a) ok = ok && (box.periodic[a] || s[a] == 0);
            if (!ok || (i == j && sx == 0 && sy == 0 && sz == 0)) continue;
            const Vec3 d = p.position[j] + box.shift_vector(s) - p.position[i];
            const double sum = p.radius[i] + p.radius[j];
            const double h = (sum - norm(d)) / sum;
            worst = std::max(worst, h);
          }
  return worst;
}

namespace {

// Independent check through the core neighbour list: max relative overlap at the given radii.
double list_max_overlap(const Packing& p) {
  std::vector<Vec3> pos = p.position;
  NeighborList list(0.0);
  list.build(p.box, pos, p.radius, 1);
  double worst = 0.0;
  const int n = static_cast<int>(p.size());
  for (int i = 0; i < n; ++i)
    for (int k = list.first(i); k < list.first(i + 1); ++k) {
      const int j = list.partner()[static_cast<std::size_t>(k)];
      const Vec3 d = pos[static_cast<std::size_t>(j)] + list.image_offset(list.image()[static_cast<std::size_t>(k)]) -
                     pos[static_cast<std::size_t>(i)];
      const double sum = p.radius[static_cast<std::size_t>(i)] + p.radius[static_cast<std::size_t>(j)];
      worst = std::max(worst, (sum - norm(d)) / sum);
    }
  return worst;
}

}  // namespace

FbaRun::FbaRun(const Box& box, std::vector<double> relative_radius, const FbaParams& params, Random& rng,
               long history_every)
    : box_(box), rho_(std::move(relative_radius)), params_(params), history_every_(history_every) {
  setup();
  // Start: uniform random centres; open axes keep whole (target) spheres inside.
  pos_.resize(rho_.size());
  for (std::size_t i = 0; i < rho_.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      const double m = box_.periodic[a] ? 0.0 : target_[i];
      pos_[i][a] = box_.lo[a] + rng.uniform(m, box_.length[a] - m);
    }
}

void FbaRun::setup() {
  params_.validate();
  const std::size_t n = rho_.size();
  require(n >= 1 && n <= 100'000'000, "particles", static_cast<double>(n), "in [1, 1e8]");
  // Positions, radii, displacements, cell lists: about 200 bytes per sphere.
  require_memory("particles", static_cast<double>(n), static_cast<double>(n), 200.0);
  for (int a = 0; a < 3; ++a)
    require(box_.length[a] > 0.0 && std::isfinite(box_.length[a]), std::string("box length ") + "xyz"[a],
            box_.length[a], "> 0 m");
  double vol_rel = 0.0, rho_max = 0.0;
  for (double r : rho_) {
    require(r > 0.0 && std::isfinite(r), "relative radius", r, "> 0");
    vol_rel += 4.0 / 3.0 * std::numbers::pi * r * r * r;
    rho_max = std::max(rho_max, r);
  }
  // Target scale: sum 4/3 pi (s rho)^3 = (1 - porosity) V.
  s_t_ = std::cbrt((1.0 - params_.target_porosity) * box_.volume() / vol_rel);
  const double s_fill = std::min(std::cbrt(box_.volume() / vol_rel), 1.5 * s_t_);  // volume fraction 1, capped
  skin_ = 0.4 * s_t_ * rho_max;                                                    // neighbour-list skin
  for (int a = 0; a < 3; ++a) {
    const double need = box_.periodic[a] ? 2.0 * s_fill * rho_max + skin_ : 2.0 * s_t_ * rho_max;
    if (box_.length[a] < need)
      fail_input(
          fmt::format("box length {} = {:g} m: must be >= {:g} m (the largest sphere{}); use a larger box "
                      "or more particles",
                      "xyz"[a], box_.length[a], need, box_.periodic[a] ? " and its images" : ""));
  }
  target_.resize(n);
  w3_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    target_[i] = s_t_ * rho_[i];
    w3_[i] = rho_[i] * rho_[i] * rho_[i];
  }
  outer_.resize(n);
  disp_.resize(n);
  last_move_.assign(n, Vec3{});
  list_.set_skin(skin_);
  s_out_ = s_fill;
  status_.porosity = params_.target_porosity;
}

bool FbaRun::run(long iterations, const std::function<void(const FbaStatus&)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const double seconds0 = seconds_;
  for (long done = 0; !finished_ && (iterations < 0 || done < iterations); ++done) {
    seconds_ = seconds0 + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    iterate(progress);
  }
  seconds_ = seconds0 + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finished_;
}

// Iteration iteration_: the overlaps at the nominal scale, the stop test, then (unless stopped)
// the moves and the new nominal scale.
void FbaRun::iterate(const std::function<void(const FbaStatus&)>& progress) {
  const std::size_t n = rho_.size();
  for (std::size_t i = 0; i < n; ++i) outer_[i] = s_out_ * rho_[i];
  if (!built_ || list_.needs_rebuild(pos_, outer_)) {
    list_.build(box_, pos_, outer_, params_.threads);
    built_ = true;
  }
  std::fill(disp_.begin(), disp_.end(), Vec3{});
  double s_in = s_out_;
  long overlapping = 0;
  for (int i = 0; i < static_cast<int>(n); ++i) {
    const auto ui = static_cast<std::size_t>(i);
    for (int k = list_.first(i); k < list_.first(i + 1); ++k) {
      const auto uk = static_cast<std::size_t>(k);
      const auto uj = static_cast<std::size_t>(list_.partner()[uk]);
      if (uj == ui) continue;  // own image: excluded by the box-size check in setup()
      const Vec3 d = pos_[uj] + list_.image_offset(list_.image()[uk]) - pos_[ui];
      const double dist = norm(d);
      const double sum = rho_[ui] + rho_[uj];
      s_in = std::min(s_in, dist / sum);
      const double h = s_out_ * sum - dist;
      if (h <= 0.0 || dist <= 0.0) continue;
      ++overlapping;
      const Vec3 u = d * (params_.step * h / dist);
      const double wi = w3_[uj] / (w3_[ui] + w3_[uj]);
      disp_[ui] -= u * wi;
      disp_[uj] += u * (1.0 - wi);
    }
  }
  FbaStatus& st = status_;
  st.iteration = iteration_;
  st.outer_scale = s_out_ / s_t_;
  st.inner_scale = s_in / s_t_;
  st.max_overlap = std::max(0.0, 1.0 - s_in / s_t_);
  st.overlapping_pairs = overlapping;
  st.seconds = seconds_;
  const bool done = st.max_overlap <= params_.tolerance;
  const bool out_of_iterations = !done && iteration_ >= params_.max_iterations;
  if (done) st.stop = FbaStop::target_reached;
  const long it = iteration_;
  if (history_every_ > 0 && (it % history_every_ == 0 || done || out_of_iterations)) history_.push_back(st);
  if (progress && (it % 50 == 0 || done || out_of_iterations)) progress(st);
  if (done || out_of_iterations) {
    finished_ = true;
    return;
  }
  // Heavy ball (fba.hpp) once the nominal scale is at the target (max() below sets it exactly).
  const bool at_target = s_out_ == s_t_ && params_.momentum > 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 m = disp_[i];
    if (at_target) m += last_move_[i] * params_.momentum;
    const double len = norm(m), cap = params_.max_move * target_[i];
    if (len > cap) m *= cap / len;
    const Vec3 before = pos_[i];
    pos_[i] += m;
    for (int a = 0; a < 3; ++a)
      if (!box_.periodic[a]) pos_[i][a] = std::clamp(pos_[i][a], box_.lo[a] + target_[i], box_.hi()[a] - target_[i]);
    if (at_target) last_move_[i] = pos_[i] - before;
  }
  s_out_ = std::max(s_t_, s_out_ - params_.shrink_rate * (s_out_ - s_in));
  ++iteration_;
}

FbaResult FbaRun::result() const {
  FbaResult result;
  Packing& p = result.packing;
  p.box = box_;
  for (std::size_t i = 0; i < rho_.size(); ++i) p.add(box_.wrap(pos_[i]), target_[i], particle_type::structural);
  result.status = status_;
  result.history = history_;
  result.verified_max_overlap = list_max_overlap(p);
  if (status_.stop == FbaStop::target_reached && result.verified_max_overlap > params_.tolerance * (1.0 + 1e-9) + 1e-12)
    throw std::logic_error(fmt::format("fba: independent check found overlap {:g} > tolerance {:g}",
                                       result.verified_max_overlap, params_.tolerance));
  return result;
}

void FbaRun::save_state(std::ostream& out) const {
  binary::write(out, box_);
  binary::write_vector(out, rho_);
  binary::write(out, params_);
  binary::write(out, history_every_);
  binary::write_vector(out, pos_);
  binary::write(out, s_out_);
  binary::write(out, iteration_);
  binary::write(out, static_cast<std::uint8_t>(finished_));
  binary::write(out, status_);
  binary::write_vector(out, history_);
  binary::write(out, seconds_);
  binary::write(out, static_cast<std::uint8_t>(built_));
  if (built_) list_.save(out);
  binary::write_vector(out, last_move_);
}

FbaRun FbaRun::load_state(std::istream& in, int threads) {
  FbaRun r;
  std::uint8_t finished = 0, built = 0;
  binary::read(in, r.box_, "box");
  binary::read_vector(in, r.rho_, "radii");
  binary::read(in, r.params_, "parameters");
  binary::read(in, r.history_every_, "history_every");
  if (threads > 0) r.params_.threads = threads;
  r.setup();  // checks the box, radii and parameters as a new run does
  binary::read_vector(in, r.pos_, "positions");
  binary::read(in, r.s_out_, "nominal scale");
  binary::read(in, r.iteration_, "iteration");
  binary::read(in, finished, "stop flag");
  binary::read(in, r.status_, "status");
  binary::read_vector(in, r.history_, "history");
  binary::read(in, r.seconds_, "seconds");
  binary::read(in, built, "neighbour list flag");
  if (r.pos_.size() != r.rho_.size() || r.iteration_ < 0 || !(r.s_out_ > 0.0))
    fail_input("checkpoint is damaged: force-biased state out of range");
  r.finished_ = finished != 0;
  r.built_ = built != 0;
  if (r.built_) r.list_.load(in);
  binary::read_vector(in, r.last_move_, "last moves");
  if (r.last_move_.size() != r.rho_.size()) fail_input("checkpoint is damaged: force-biased state out of range");
  return r;
}

FbaResult fba_pack(const Box& box, const std::vector<double>& relative_radius, const FbaParams& params, Random& rng,
                   long history_every, const std::function<void(const FbaStatus&)>& progress) {
  FbaRun run(box, relative_radius, params, rng, history_every);
  run.run(-1, progress);
  return run.result();
}

std::array<bool, 3> periodic_axes_from_name(const std::string& s) {
  std::array<bool, 3> p{false, false, false};
  if (s == "none") return p;
  for (char c : s) {
    const auto k = std::string("xyz").find(c);
    if (k == std::string::npos || p[k])
      fail_input("periodic = " + s + ": must be a subset of xyz without repeats (e.g. xy, xyz) or none");
    p[k] = true;
  }
  return p;
}

}  // namespace packlab::generate
