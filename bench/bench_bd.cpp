// Brownian-dynamics coagulation (docs/bd.md): N spheres at Phi = 0.4 (the paper's setting),
// default DLVO parameters at the given surface potential, a fixed number of steps after the
// start: particle-steps/s of the step loop (DLVO pairs within the cut-off, bonds, the
// Ermak-McCammon update with three normals per sphere), bonds formed, neighbour rebuilds.
// usage: bench_bd [N] [STEPS] [PSI_MV] [SEED] [THREADS]
// last line: packlab bd N=... steps=... threads=... rate=... particle-steps/s
#include <fmt/format.h>

#include <cstdlib>

#include "packlab/core/thread_wait.hpp"
#include "packlab/generate/brownian_dynamics.hpp"

using namespace packlab;
using namespace packlab::generate;

int main(int argc, char** argv) {
  ensure_passive_thread_wait(argv);  // as the packlab program does (core/thread_wait.hpp)
  BdParams p;
  p.particles = argc > 1 ? std::atol(argv[1]) : 8000;
  const long steps = argc > 2 ? std::atol(argv[2]) : 2000;
  p.surface_potential = (argc > 3 ? std::atof(argv[3]) : 15.0) * 1e-3;
  const std::uint64_t seed = argc > 4 ? std::strtoull(argv[4], nullptr, 10) : 1;
  p.threads = argc > 5 ? std::atoi(argv[5]) : 1;
  p.duration = 1e6;  // the run is cut by `steps`
  p.samples = 1;
  p.quench_steps = 0;
  BdRun run(p, Random(seed));
  run.run(steps);
  const BdResult r = run.result();
  const double rate = static_cast<double>(steps) * static_cast<double>(p.particles) / r.status.seconds;
  fmt::print("bd: N={} phi={:g} psi0={:g} mV dt={:.3g} s steps={} t={:.4g} a^2/D0 bonds={} threads={} time={:.2f} s\n",
             p.particles, p.volume_fraction, 1e3 * p.surface_potential, r.time_step, steps,
             static_cast<double>(steps) * r.time_step / p.diffusion_time(), r.status.bonds, p.threads,
             r.status.seconds);
  fmt::print("packlab bd N={} steps={} threads={} rate={:.4g} particle-steps/s\n", p.particles, steps, p.threads, rate);
  return 0;
}
