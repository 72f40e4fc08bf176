// Force-biased algorithm and inverse-opal builder (docs/opal-build.md).
//  1. FBA: N equal spheres (default 50,000) to porosity 0.38, periodic along x, y, walls along z
//     (the paper's setting), tolerance 1e-3: iterations (total, and the two phases: contraction
//     of the nominal diameter to the target, then removal of the last overlaps at the target),
//     CPU and wall time, particle-iterations per CPU second, the verified max overlap.
//  2. Builder: that packing with FCC [111] pores of ratio D/d = 10 (box sized to 3 x 3 x 1 pore
//     lattice periods + substrate) and a 1 d titania coating: time, particles, bonds, mean
//     coordination, bytes of the model per particle and per bond, and the peak resident memory.
// usage: bench_fba [RATIO] [SEED]
// last line: packlab fba+opal N=... fba_iterations=... fba_removal_iterations=... fba_cpu_s=... ...
//
//        bench_fba seeds N K [classic]
//  FBA only: N equal spheres in the demo's box shape (20 x 34.6 x 26.5 d, periodic x y, walls
//  z) scaled to porosity 0.38, seeds 1..K; per seed one line `fba_seed ...` with the iteration
//  counts, CPU time, verified overlap and the structure (contacts per particle within 1 % of
//  contact, g(r) at its first peak and second-peak split), then their means and scatter.
//  `classic` runs the first version (no momentum in the overlap removal: see FbaParams) for the
//  before/after comparison in one run.
#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <string>
#include <vector>

#include "packlab/analyze/coordination.hpp"
#include "packlab/analyze/rdf.hpp"
#include "packlab/core/thread_wait.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/generate/opal.hpp"

using namespace packlab;
using namespace packlab::generate;

namespace {

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // Linux: kB
}

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// Iterations while the nominal diameter is above the target (contraction), the rest at the
// target (removal of the last overlaps), from a history recorded every iteration.
struct Phases {
  long contraction = 0, removal = 0;
};
Phases phases_of(const FbaResult& r) {
  Phases p;
  for (const FbaStatus& s : r.history)
    if (s.iteration < r.status.iteration) (s.outer_scale > 1.0 ? p.contraction : p.removal) += 1;
  return p;
}

struct Sample {
  long iterations = 0, removal = 0;
  double cpu = 0, overlap = 0, porosity = 0, contacts = 0, g_peak = 0, g_at_sqrt3 = 0, g_at_2 = 0;
};

double mean_of(const std::vector<Sample>& v, double Sample::*f) {
  double s = 0;
  for (const auto& x : v) s += x.*f;
  return s / static_cast<double>(v.size());
}
double sd_of(const std::vector<Sample>& v, double Sample::*f) {
  const double m = mean_of(v, f);
  double s = 0;
  for (const auto& x : v) s += (x.*f - m) * (x.*f - m);
  return v.size() > 1 ? std::sqrt(s / static_cast<double>(v.size() - 1)) : 0.0;
}

int seeds_mode(long n, int k, bool classic) {
  // The demo's box shape, scaled to N spheres of unit diameter at porosity 0.38.
  const Vec3 aspect{20.0, 34.641, 26.495};
  const double volume = static_cast<double>(n) * std::numbers::pi / 6.0 / 0.62;
  const double f = std::cbrt(volume / (aspect.x * aspect.y * aspect.z));
  Box box;
  box.length = aspect * f;
  box.periodic = {true, true, false};
  FbaParams fp;
  if (classic) fp.momentum = 0.0;  // the first version (fba.hpp)
  std::vector<Sample> all;
  for (int seed = 1; seed <= k; ++seed) {
    Random rng(static_cast<std::uint64_t>(seed));
    SizeClasses mono;
    const double c0 = cpu_seconds();
    const FbaResult r = fba_pack(box, fba_class_radii(n, mono, rng), fp, rng, 1);
    Sample s;
    s.cpu = cpu_seconds() - c0;
    const Phases ph = phases_of(r);
    s.iterations = r.status.iteration;
    s.removal = ph.removal;
    s.overlap = r.verified_max_overlap;
    s.porosity = 1.0 - r.packing.volume_fraction();
    analyze::Coordination cn(0.01);
    cn.compute(r.packing);
    s.contacts = cn.mean();
    analyze::RdfParams rp;
    rp.dr = 0.02;
    rp.r_max = 5.0;
    rp.threads = 1;
    analyze::Rdf rdf(rp);
    rdf.compute(r.packing);
    const std::vector<double> g = rdf.g(), R = rdf.reduced_r();
    // Radii units: contact at R = 2; first peak in [2, 2.3); second-peak split at 2 sqrt3, 4.
    for (std::size_t b = 0; b < g.size(); ++b) {
      if (R[b] >= 2.0 && R[b] < 2.3) s.g_peak = std::max(s.g_peak, g[b]);
      if (std::abs(R[b] - 2.0 * std::sqrt(3.0)) < 0.011) s.g_at_sqrt3 = g[b];
      if (std::abs(R[b] - 4.0) < 0.011) s.g_at_2 = g[b];
    }
    fmt::print(
        "fba_seed schedule={} N={} seed={} stop={} iterations={} contraction_iterations={} "
        "removal_iterations={} cpu_s={:.2f} porosity={:.6f} verified_max_overlap={:.4g} contacts_per_particle={:.4f} "
        "g_first_peak={:.3f} g_2sqrt3={:.3f} g_4={:.3f}\n",
        classic ? "momentum_0" : "momentum_0.9", n, seed, fba_stop_name(r.status.stop), s.iterations, ph.contraction,
        ph.removal, s.cpu, s.porosity, s.overlap, s.contacts, s.g_peak, s.g_at_sqrt3, s.g_at_2);
    std::fflush(stdout);
    all.push_back(s);
  }
  std::vector<double> it, rm;
  for (const auto& s : all) {
    it.push_back(static_cast<double>(s.iterations));
    rm.push_back(static_cast<double>(s.removal));
  }
  double mi = 0, mr = 0;
  for (std::size_t q = 0; q < it.size(); ++q) mi += it[q], mr += rm[q];
  mi /= static_cast<double>(it.size());
  mr /= static_cast<double>(rm.size());
  fmt::print(
      "fba_summary schedule={} N={} seeds={} iterations_mean={:.0f} removal_iterations_mean={:.0f} "
      "cpu_s_mean={:.2f} contacts_per_particle={:.4f}+-{:.4f} g_first_peak={:.3f}+-{:.3f} "
      "g_2sqrt3={:.3f}+-{:.3f} g_4={:.3f}+-{:.3f} max_verified_overlap={:.4g}\n",
      classic ? "momentum_0" : "momentum_0.9", n, k, mi, mr, mean_of(all, &Sample::cpu),
      mean_of(all, &Sample::contacts), sd_of(all, &Sample::contacts), mean_of(all, &Sample::g_peak),
      sd_of(all, &Sample::g_peak), mean_of(all, &Sample::g_at_sqrt3), sd_of(all, &Sample::g_at_sqrt3),
      mean_of(all, &Sample::g_at_2), sd_of(all, &Sample::g_at_2),
      std::max_element(all.begin(), all.end(), [](const Sample& a, const Sample& b) {
        return a.overlap < b.overlap;
      })->overlap);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  ensure_passive_thread_wait(argv);  // as the packlab program does (core/thread_wait.hpp)
  if (argc > 1 && std::string(argv[1]) == "seeds") {
    const long n = argc > 2 ? std::atol(argv[2]) : 10000;
    const int k = argc > 3 ? std::atoi(argv[3]) : 3;
    const bool classic = argc > 4 && std::string(argv[4]) == "classic";
    return seeds_mode(n, k, classic);
  }
  const double ratio = argc > 1 ? std::atof(argv[1]) : 10.0;
  const std::uint64_t seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1;
  // Box: 3 x 3 x 1 periods of the [111] pore lattice (touching pores of diameter ratio x d) plus
  // a two-diameter substrate slab; unit particle diameter.
  FccPores fcc;
  fcc.diameter = ratio;
  const Vec3 per = fcc_pore_period(fcc);
  Box box;
  box.length = {3 * per.x, 3 * per.y, per.z + 2.0};
  box.periodic = {true, true, false};
  SizeClasses mono;
  const long n = fba_count_for_volume(box.volume(), 0.38, 1.0, mono);
  Random rng(seed);
  FbaParams fp;
  const double rss0 = peak_rss_mb();
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = cpu_seconds();
  const FbaResult fba = fba_pack(box, fba_class_radii(n, mono, rng), fp, rng, 1);
  const double fba_cpu = cpu_seconds() - c0;
  const double fba_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double rss_fba = peak_rss_mb();
  const Phases ph = phases_of(fba);
  fmt::print(
      "fba: N={} box={:.2f}x{:.2f}x{:.2f} d periodic=xy porosity={:.6f} stop={} iterations={} "
      "(contraction {}, overlap removal at the target {}) time={:.2f} s cpu={:.2f} s "
      "rate={:.3g} particle-iterations/cpu-s max_overlap={:.3g} (verified {:.3g}, tolerance {:g}) peak_rss={:.0f} MB\n",
      n, box.length.x, box.length.y, box.length.z, 1.0 - fba.packing.volume_fraction(), fba_stop_name(fba.status.stop),
      fba.status.iteration, ph.contraction, ph.removal, fba_s, fba_cpu,
      static_cast<double>(fba.status.iteration) * static_cast<double>(n) / fba_cpu, fba.status.max_overlap,
      fba.verified_max_overlap, fp.tolerance, rss_fba);

  double opal0_s = 0;
  long bonds0 = 0;
  for (double coating : {0.0, 1.0}) {
    OpalOptions o;
    o.fcc = fcc;
    o.coating_thickness = coating;
    OpalSummary s;
    const auto t1 = std::chrono::steady_clock::now();
    const Packing model = build_opal(fba.packing, o, &s);
    const double opal_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    // Bytes held by the model: position 24 + radius 8 + type 4 + fixed 1 per particle;
    // i, j 8 + image 12 + material 4 + rest length 8 + state 4 per bond.
    const double bytes_particle = 37.0, bytes_bond = 36.0;
    const double model_mb =
        (bytes_particle * static_cast<double>(model.size()) + bytes_bond * static_cast<double>(model.bonds.size())) /
        1048576.0;
    fmt::print(
        "opal: ratio D/d={:g} coating={:g} d: {} -> {} particles ({} silica, {} titania, {} substrate), {} bonds "
        "({} silica, {} titania, {} substrate, {} periodic), CN={:.3f}, porosity={:.4f}, density={:.1f} kg/m^3, "
        "{} pores, time={:.3f} s ({:.3g} us/particle, {:.3g} us/bond), model={:.1f} MB ({:.0f} B/particle + "
        "{:.0f} B/bond), peak_rss={:.0f} MB (start {:.0f} MB)\n",
        ratio, coating, s.input_particles, s.particles, s.structural, s.coating, s.substrate, s.bonds,
        s.bonds_by_material[0], s.bonds_by_material[1], s.bonds_by_material[2], s.periodic_bonds, s.mean_coordination,
        s.porosity, s.density, s.pores, opal_s, 1e6 * opal_s / static_cast<double>(s.input_particles),
        1e6 * opal_s / static_cast<double>(s.bonds), model_mb, bytes_particle, bytes_bond, peak_rss_mb(), rss0);
    if (coating == 0.0) {
      opal0_s = opal_s;
      bonds0 = s.bonds;
    }
  }
  fmt::print(
      "packlab fba+opal N={} fba_iterations={} fba_removal_iterations={} fba_s={:.3f} fba_cpu_s={:.3f} "
      "fba_rate={:.4g} opal_s={:.3f} bonds={} bytes_per_bond=36\n",
      n, fba.status.iteration, ph.removal, fba_s, fba_cpu,
      static_cast<double>(fba.status.iteration) * static_cast<double>(n) / fba_cpu, opal0_s, bonds0);
  return 0;
}
