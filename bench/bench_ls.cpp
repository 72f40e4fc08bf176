// Lubachevsky-Stillinger growth: wall time, collisions/s and events/s to jamming (or to a target
// volume fraction), for the cases of ../shared/peers/README.md (PackingGeneration's LS timings).
// usage: bench_ls [N] [GROWTH_RATE] [TARGET_PHI (0 = jam)] [SIZE_RATIO (1 = mono)] [SMALL/LARGE VOLUME RATIO]
//                 [MAX_PRESSURE] [SEED]
// e.g.   bench_ls 10000 0.02            mono to jamming
//        bench_ls 10000 0.02 0.6 0.313 0.333   bimodal case of the paper to c = 0.6
// last line: packlab ls N=... phi=... wall_s=... ls_cpu_s=... collisions_per_cpu_s=... events_per_cpu_s=...
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>

#include "packlab/generate/ls.hpp"

using namespace packlab;

int main(int argc, char** argv) {
  const long n = argc > 1 ? std::atol(argv[1]) : 10000;
  const double rate = argc > 2 ? std::atof(argv[2]) : 0.02;
  const double target = argc > 3 ? std::atof(argv[3]) : 0.0;
  const double ratio = argc > 4 ? std::atof(argv[4]) : 1.0;
  const double vol_ratio = argc > 5 ? std::atof(argv[5]) : 0.333;
  const double pmax = argc > 6 ? std::atof(argv[6]) : 1e12;
  const unsigned long seed = argc > 7 ? std::strtoul(argv[7], nullptr, 10) : 42;
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
  generate::LsSimulation sim(start.box, start.points, start.unit_radius, p, rng);
  long last_print = 0;
  const generate::LsStatus s = sim.run([&](const generate::LsStatus& st) {
    if (st.blocks - last_print >= 10) {
      last_print = st.blocks;
      fmt::print(stderr, "  block {} phi {:.6f} p {:.4g} collisions {} t {:.1f} s\n", st.blocks, st.volume_fraction,
                 st.reduced_pressure, st.collisions, st.seconds);
    }
  });
  const Packing packing = sim.packing();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fmt::print("stop={} blocks={} reduced_pressure={:.4g} stale={} transfers={} overlap_correction={:.3g}\n",
             generate::ls_stop_name(s.stop), s.blocks, s.reduced_pressure, s.stale, s.transfers,
             sim.overlap_correction());
  fmt::print("packlab ls N={} rate={} phi={:.5f} collisions={} wall_s={:.2f} ls_cpu_s={:.2f} collisions_per_cpu_s={:.4g} "
             "events_per_cpu_s={:.4g}\n",
             n, rate, packing.volume_fraction(), s.collisions, wall, s.cpu_seconds,
             static_cast<double>(s.collisions) / s.cpu_seconds, static_cast<double>(s.events()) / s.cpu_seconds);
  return 0;
}
