#include "packlab/generate/fba.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

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

FbaResult fba_pack(const Box& box, const std::vector<double>& relative_radius, const FbaParams& params, Random& rng,
                   long history_every, const std::function<void(const FbaStatus&)>& progress) {
  params.validate();
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = relative_radius.size();
  require(n >= 1 && n <= 100'000'000, "particles", static_cast<double>(n), "in [1, 1e8]");
  // Positions, radii, displacements, cell lists: about 200 bytes per sphere.
  require_memory("particles", static_cast<double>(n), static_cast<double>(n), 200.0);
  for (int a = 0; a < 3; ++a)
    require(box.length[a] > 0.0 && std::isfinite(box.length[a]), std::string("box length ") + "xyz"[a], box.length[a],
            "> 0 m");
  double vol_rel = 0.0, rho_max = 0.0;
  for (double r : relative_radius) {
    require(r > 0.0 && std::isfinite(r), "relative radius", r, "> 0");
    vol_rel += 4.0 / 3.0 * std::numbers::pi * r * r * r;
    rho_max = std::max(rho_max, r);
  }
  // Target scale: sum 4/3 pi (s rho)^3 = (1 - porosity) V.
  const double s_t = std::cbrt((1.0 - params.target_porosity) * box.volume() / vol_rel);
  const double s_fill = std::min(std::cbrt(box.volume() / vol_rel), 1.5 * s_t);  // volume fraction 1, capped
  const double skin = 0.4 * s_t * rho_max;                                       // neighbour-list skin
  for (int a = 0; a < 3; ++a) {
    const double need = box.periodic[a] ? 2.0 * s_fill * rho_max + skin : 2.0 * s_t * rho_max;
    if (box.length[a] < need)
      fail_input(
          fmt::format("box length {} = {:g} m: must be >= {:g} m (the largest sphere{}); use a larger box "
                      "or more particles",
                      "xyz"[a], box.length[a], need, box.periodic[a] ? " and its images" : ""));
  }

  std::vector<double> target(n), outer(n), w3(n);
  for (std::size_t i = 0; i < n; ++i) {
    target[i] = s_t * relative_radius[i];
    w3[i] = relative_radius[i] * relative_radius[i] * relative_radius[i];
  }
  // Start: uniform random centres; open axes keep whole (target) spheres inside.
  std::vector<Vec3> pos(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      const double m = box.periodic[a] ? 0.0 : target[i];
      pos[i][a] = box.lo[a] + rng.uniform(m, box.length[a] - m);
    }

  double s_out = s_fill;
  NeighborList list(skin);
  std::vector<Vec3> disp(n);
  FbaResult result;
  FbaStatus st;
  st.porosity = params.target_porosity;
  bool built = false;
  for (long it = 0;; ++it) {
    for (std::size_t i = 0; i < n; ++i) outer[i] = s_out * relative_radius[i];
    if (!built || list.needs_rebuild(pos, outer)) {
      list.build(box, pos, outer, params.threads);
      built = true;
    }
    std::fill(disp.begin(), disp.end(), Vec3{});
    double s_in = s_out;
    long overlapping = 0;
    for (int i = 0; i < static_cast<int>(n); ++i) {
      const auto ui = static_cast<std::size_t>(i);
      for (int k = list.first(i); k < list.first(i + 1); ++k) {
        const auto uk = static_cast<std::size_t>(k);
        const auto uj = static_cast<std::size_t>(list.partner()[uk]);
        if (uj == ui) continue;  // own image: excluded by the box-size check above
        const Vec3 d = pos[uj] + list.image_offset(list.image()[uk]) - pos[ui];
        const double dist = norm(d);
        const double sum = relative_radius[ui] + relative_radius[uj];
        s_in = std::min(s_in, dist / sum);
        const double h = s_out * sum - dist;
        if (h <= 0.0 || dist <= 0.0) continue;
        ++overlapping;
        const Vec3 u = d * (params.step * h / dist);
        const double wi = w3[uj] / (w3[ui] + w3[uj]);
        disp[ui] -= u * wi;
        disp[uj] += u * (1.0 - wi);
      }
    }
    st.iteration = it;
    st.outer_scale = s_out / s_t;
    st.inner_scale = s_in / s_t;
    st.max_overlap = std::max(0.0, 1.0 - s_in / s_t);
    st.overlapping_pairs = overlapping;
    st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const bool done = st.max_overlap <= params.tolerance;
    const bool out_of_iterations = !done && it >= params.max_iterations;
    if (done) st.stop = FbaStop::target_reached;
    if (history_every > 0 && (it % history_every == 0 || done || out_of_iterations)) result.history.push_back(st);
    if (progress && (it % 50 == 0 || done || out_of_iterations)) progress(st);
    if (done || out_of_iterations) break;

    for (std::size_t i = 0; i < n; ++i) {
      Vec3 m = disp[i];
      const double len = norm(m), cap = params.max_move * target[i];
      if (len > cap) m *= cap / len;
      pos[i] += m;
      for (int a = 0; a < 3; ++a)
        if (!box.periodic[a]) pos[i][a] = std::clamp(pos[i][a], box.lo[a] + target[i], box.hi()[a] - target[i]);
    }
    s_out = std::max(s_t, s_out - params.shrink_rate * (s_out - s_in));
  }

  Packing& p = result.packing;
  p.box = box;
  for (std::size_t i = 0; i < n; ++i) p.add(box.wrap(pos[i]), target[i], particle_type::structural);
  result.status = st;
  result.verified_max_overlap = list_max_overlap(p);
  if (st.stop == FbaStop::target_reached && result.verified_max_overlap > params.tolerance * (1.0 + 1e-9) + 1e-12)
    throw std::logic_error(fmt::format("fba: independent check found overlap {:g} > tolerance {:g}",
                                       result.verified_max_overlap, params.tolerance));
  return result;
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
