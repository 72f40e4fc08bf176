// Benchmark case "relax" exactly as ../shared/peers/dem/common.sh defines it: 8000 spheres,
// r = 0.25 um, rho = 3690 kg/m3, Park-Miller random centres (seed 12345) in a periodic cube at
// nominal phi 0.70, kn = 1000 N/m, ks = 10 N/m, mu = 0.1, dt = 0.2 sqrt(m/kn), 20,000 steps.
// packlab uses Cundall local damping 0.7 (as YADE); LAMMPS uses viscous damping 0.3.
// usage: bench_relax [THREADS] [STEPS] [fixed|adaptive] [FRICTION]; "fixed": no switching to one
// thread when that is faster (EngineConfig::adapt_threads, on by default); FRICTION replaces the
// case's mu = 0.1 (0: the frictionless contacts of the void expansion method); last line: packlab relax N=... pts_per_s=...
// bytes_per_particle=... (the engine's heap by part on the line before, bench/memory_report.hpp)
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>

#include "memory_report.hpp"
#include "packlab/core/thread_wait.hpp"
#include "packlab/dem/engine.hpp"

using namespace packlab;

int main(int argc, char** argv) {
  ensure_passive_thread_wait(argv);  // as the packlab program does (core/thread_wait.hpp)
  const int threads = argc > 1 ? std::atoi(argv[1]) : 1;
  const long steps = argc > 2 ? std::atol(argv[2]) : 20000;
  const bool fixed_threads = argc > 3 && std::string(argv[3]) == "fixed";
  const long n = 8000;
  const double mu = argc > 4 ? std::atof(argv[4]) : 0.1;
  const double radius = 0.25e-6, density = 3690, phi = 0.70, kn = 1000, ks = 10;
  const double volume = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  const double mass = volume * density;
  const double edge = std::cbrt(static_cast<double>(n) * volume / phi);
  Packing packing;
  packing.box.length = {edge, edge, edge};
  // Park-Miller minimal standard LCG, exact in double precision as in common.sh.
  double s = 12345;
  auto rnd = [&] {
    s = std::fmod(16807.0 * s, 2147483647.0);
    return s / 2147483647.0;
  };
  for (long i = 0; i < n; ++i) {
    const double x = rnd() * edge, y = rnd() * edge, z = rnd() * edge;
    packing.add({x, y, z}, radius);
  }
  dem::EngineConfig config;
  config.types = {dem::Material{kn, ks, mu, density, 0.7}};
  config.stiffness_rule = dem::StiffnessRule::contact;
  config.time_step = 0.2 * std::sqrt(mass / kn);
  config.skin_ratio = 0.2;  // 0.1 d, as the LAMMPS script's neighbor skin
  config.threads = threads;
  config.adapt_threads = !fixed_threads;
  dem::Engine engine(packing, config);
  const auto t0 = std::chrono::steady_clock::now();
  engine.run(steps - 1);
  const dem::Diagnostics d = engine.step_measured();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fmt::print(
      "packlab threads={} ({}; {} at the end, {} switches) final mean contacts/particle={:.3f} unbalanced={:.3g} "
      "neighbor_builds={}\n",
      threads, fixed_threads ? "fixed" : "adaptive", engine.active_threads(), engine.thread_switches(),
      d.mean_coordination, d.unbalanced_force_ratio, engine.neighbor_builds());
  bench::print_engine_memory(engine);
  fmt::print("packlab relax N={} steps={}{} wall_s={:.3f} pts_per_s={:.4g} bytes_per_particle={:.0f}\n", n, steps,
             mu == 0.1 ? std::string() : fmt::format(" friction={:g}", mu), wall,
             static_cast<double>(n) * static_cast<double>(steps) / wall,
             static_cast<double>(engine.memory().total()) / static_cast<double>(n));
  return 0;
}
