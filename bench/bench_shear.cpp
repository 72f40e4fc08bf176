// Benchmark of the oscillatory shear test (doh-elastic-properties §2.4), one orientation (plate
// normal z, shear x) of the N = 8000 case: the VEM structure N_S = 8000, N_V = 2000, Phi = 0.4,
// r = 0.25 um (examples/shear/data/vem_ns8000_nv2000.xyz), contact bonds at (1 + 0.01) 2r,
// Table 1 parameters (k_n = 100, k_s = 10 N/m particle stiffnesses, damping 0.9, rho = 3690).
// usage: bench_shear [FILE] [THREADS] [STEPS_PER_CYCLE] [CYCLES] [fixed]; "fixed": THREADS from
// the first step (adapt_threads off: an adapting engine starts at one thread, docs/engine.md)
// last line: packlab shear N=... bonds=... steps=... wall_s=... pts_per_s=...
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <string>

#include "packlab/core/thread_wait.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/mechanics/oscillatory_shear.hpp"
#include "shear_case.hpp"

using namespace packlab;

int main(int argc, char** argv) {
  ensure_passive_thread_wait(argv);  // as the packlab program does (core/thread_wait.hpp)
  const bool fixed_threads = argc > 1 && std::string(argv[argc - 1]) == "fixed";
  if (fixed_threads) --argc;
  const std::string file = argc > 1 ? argv[1] : "examples/shear/data/vem_ns8000_nv2000.xyz";
  const int threads = argc > 2 ? std::atoi(argv[2]) : 1;
  const long steps_per_cycle = argc > 3 ? std::atol(argv[3]) : 10000;
  const int cycles = argc > 4 ? std::atoi(argv[4]) : 10;
  Packing packing = bench::shear_case(file);
  mechanics::OscillatoryShearOptions o;
  o.threads = threads;
  o.adapt_threads = !fixed_threads;
  o.steps_per_cycle = steps_per_cycle;
  o.cycles = cycles;
  o.orientations = "z:x";
  auto t0 = std::chrono::steady_clock::now();
  dem::ZeroVelocityRelaxResult relax;
  const Packing relaxed = mechanics::relax_bonded(packing, o, &relax);
  const double relax_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  o.relax = false;  // relaxed above; the set-up is still settled
  t0 = std::chrono::steady_clock::now();
  const mechanics::OscillatoryShearResult r = mechanics::run_oscillatory_shear(relaxed, o);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto& run = r.runs.at(0);
  const double n = static_cast<double>(run.structure_particles + run.plate_particles);
  fmt::print("packlab threads={} ({}) relax: {} steps {:.2f} s ({})\n", threads, fixed_threads ? "fixed" : "adaptive",
             relax.steps, relax_s, relax.reason());
  fmt::print("packlab shear G'={:.4g} Pa phase={:.3g} rad settle_steps={} loading_steps={} dt={:.4g} s\n",
             run.storage_modulus, run.phase_angle, run.settle.steps, run.steps - run.settle.steps, run.time_step);
  fmt::print("packlab shear N={} structure={} bonds={} steps={} wall_s={:.3f} pts_per_s={:.4g}\n", static_cast<long>(n),
             run.structure_particles, run.bonds, run.steps, wall, n * static_cast<double>(run.steps) / wall);
  return 0;
}
