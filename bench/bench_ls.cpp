// Lubachevsky-Stillinger growth: wall time, CPU time, collisions/s and events/s to jamming (or to
// a target volume fraction), for the cases of ../shared/peers/README.md (PackingGeneration's LS
// timings), and the memory of the simulation per particle (its arrays' capacities: now at the
// end, and the most at any time, the temporaries of a block's start included) beside the
// process's peak resident memory.
// usage: bench_ls [N] [GROWTH_RATE] [TARGET_PHI (0 = jam)] [SIZE_RATIO (1 = mono)] [SMALL/LARGE VOLUME RATIO]
//                 [MAX_PRESSURE] [SEED] [NEIGHBOR_LIST_LIMIT (LsParams' default; 0 = no limit)]
// e.g.   bench_ls 10000 0.02            mono to jamming
//        bench_ls 10000 0.02 0.6 0.313 0.333   bimodal case of the paper to c = 0.6
//        bench_ls 10000 0.04 0 1 0.333 1e12 42 0   to jamming without the list-length limit
// last line: packlab ls N=... phi=... wall_s=... ls_cpu_s=... collisions_per_cpu_s=... events_per_cpu_s=...
//            bytes_per_particle=... peak_bytes_per_particle=... peak_rss_per_particle=... list_limit=...
//
// With BENCH_LS_TRACE=1 in the environment, a line per block: trace block=... phi=... skin=...
// neighbors=... bytes_per_particle=... peak_bytes_per_particle=...
//
//        bench_ls scaling N1 N2 GROWTH_RATE [SEED]
// the same case (monodisperse, to jamming) at N1 and N2 particles in one run, then
// `packlab ls scaling ... cpu_ratio=... n_log_n_ratio=...`: the CPU time ratio against
// N2 log N2 / (N1 log N1) (the cost of an event calendar of N entries) and against N2 / N1.
#include <fmt/format.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>

#include "packlab/core/thread_wait.hpp"
#include "packlab/generate/ls.hpp"

using namespace packlab;

namespace {

double peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) * 1024.0;  // Linux: kB
}

struct Run {
  generate::LsStatus status;
  double phi = 0, wall = 0, bytes = 0, peak_bytes = 0;
};

Run run_case(long n, double rate, double target, double ratio, double vol_ratio, double pmax, unsigned long seed,
             double list_limit = generate::LsParams{}.neighbor_list_limit) {
  generate::SizeClasses classes;
  if (ratio != 1.0) {
    classes.sizes = {1.0, ratio};
    classes.fractions = {1.0, vol_ratio};
    classes.volume_fractions = true;
  }
  Random rng(seed);
  const auto t0 = std::chrono::steady_clock::now();
  const generate::LsStart start = generate::make_ls_start(n, classes, 0.5, target > 0 ? target : 0.64, rng);
  generate::LsParams p;
  p.growth_rate = rate;
  p.target_volume_fraction = target;
  p.max_reduced_pressure = pmax;
  p.neighbor_list_limit = list_limit;
  generate::LsSimulation sim(start.box, start.points, start.unit_radius, p, rng);
  long last_print = 0;
  Run r;
  // BENCH_LS_TRACE=1: one line per block with the lists' mean length and the memory (docs/scrm.md).
  const bool trace = std::getenv("BENCH_LS_TRACE") != nullptr;
  r.status = sim.run([&](const generate::LsStatus& st) {
    if (trace)
      fmt::print(
          "trace block={} phi={:.7f} skin={:.4f} neighbors={:.2f} bytes_per_particle={:.1f} "
          "peak_bytes_per_particle={:.1f} reduced_pressure={:.6g} collisions={} transfers={} time={:.6g}\n",
          st.blocks, st.volume_fraction, sim.neighbor_skin(), sim.mean_neighbors(),
          static_cast<double>(sim.memory_bytes()) / static_cast<double>(n),
          static_cast<double>(sim.peak_memory_bytes()) / static_cast<double>(n), st.reduced_pressure, st.collisions,
          st.transfers, st.time);
    if (st.blocks - last_print >= 10) {
      last_print = st.blocks;
      fmt::print(stderr, "  block {} phi {:.6f} p {:.4g} collisions {} t {:.1f} s\n", st.blocks, st.volume_fraction,
                 st.reduced_pressure, st.collisions, st.seconds);
    }
  });
  r.bytes = static_cast<double>(sim.memory_bytes());
  r.peak_bytes = static_cast<double>(sim.peak_memory_bytes());
  const Packing packing = sim.packing();
  r.phi = packing.volume_fraction();
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const generate::LsStatus& s = r.status;
  const double dn = static_cast<double>(n);
  fmt::print(
      "stop={} blocks={} reduced_pressure={:.6g} phi_exact={:.12f} stale={} transfers={} overlap_correction={:.3g} "
      "collisions_per_particle={:.1f}\n",
      generate::ls_stop_name(s.stop), s.blocks, s.reduced_pressure, r.phi, s.stale, s.transfers,
      sim.overlap_correction(), static_cast<double>(s.collisions) / dn);
  fmt::print(
      "packlab ls N={} rate={} phi={:.5f} collisions={} wall_s={:.2f} ls_cpu_s={:.2f} collisions_per_cpu_s={:.4g} "
      "events_per_cpu_s={:.4g} bytes_per_particle={:.0f} peak_bytes_per_particle={:.0f} "
      "peak_rss_per_particle={:.0f} list_limit={:g}\n",
      n, rate, r.phi, s.collisions, r.wall, s.cpu_seconds, static_cast<double>(s.collisions) / s.cpu_seconds,
      static_cast<double>(s.events()) / s.cpu_seconds, r.bytes / dn, r.peak_bytes / dn, peak_rss_bytes() / dn, list_limit);
  std::fflush(stdout);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  ensure_passive_thread_wait(argv);  // as the packlab program does (core/thread_wait.hpp)
  if (argc > 1 && std::string(argv[1]) == "scaling") {
    const long n1 = argc > 2 ? std::atol(argv[2]) : 10000;
    const long n2 = argc > 3 ? std::atol(argv[3]) : 100000;
    const double rate = argc > 4 ? std::atof(argv[4]) : 3.0;
    const unsigned long seed = argc > 5 ? std::strtoul(argv[5], nullptr, 10) : 42;
    const Run a = run_case(n1, rate, 0.0, 1.0, 0.333, 1e12, seed);
    const Run b = run_case(n2, rate, 0.0, 1.0, 0.333, 1e12, seed);
    const double x1 = static_cast<double>(n1), x2 = static_cast<double>(n2);
    const double e1 = static_cast<double>(a.status.events()), e2 = static_cast<double>(b.status.events());
    fmt::print(
        "packlab ls scaling N1={} N2={} rate={} cpu_s={:.2f},{:.2f} cpu_ratio={:.2f} n_ratio={:.2f} "
        "n_log_n_ratio={:.2f} events_ratio={:.2f} cpu_per_event_ratio={:.2f}\n",
        n1, n2, rate, a.status.cpu_seconds, b.status.cpu_seconds, b.status.cpu_seconds / a.status.cpu_seconds, x2 / x1,
        x2 * std::log(x2) / (x1 * std::log(x1)), e2 / e1, (b.status.cpu_seconds / e2) / (a.status.cpu_seconds / e1));
    return 0;
  }
  const long n = argc > 1 ? std::atol(argv[1]) : 10000;
  const double rate = argc > 2 ? std::atof(argv[2]) : 0.02;
  const double target = argc > 3 ? std::atof(argv[3]) : 0.0;
  const double ratio = argc > 4 ? std::atof(argv[4]) : 1.0;
  const double vol_ratio = argc > 5 ? std::atof(argv[5]) : 0.333;
  const double pmax = argc > 6 ? std::atof(argv[6]) : 1e12;
  const unsigned long seed = argc > 7 ? std::strtoul(argv[7], nullptr, 10) : 42;
  const double list_limit = argc > 8 ? std::atof(argv[8]) : generate::LsParams{}.neighbor_list_limit;
  run_case(n, rate, target, ratio, vol_ratio, pmax, seed, list_limit);
  return 0;
}
