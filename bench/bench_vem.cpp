// End-to-end benchmark of the void expansion method (vem-void-expansion-method Fig. 1 case by
// default: N_S = 8000, N_V = 2000, Phi_S = 0.4, Table 1 parameters, stop at stage III).
// usage: bench_vem [THREADS] [N_S] [N_V] [PHI_S] [MAX_CYCLES] [SKIN] [fixed]; "fixed": THREADS
// from the first step (adapt_threads off: an adapting engine starts at one thread)
//   MAX_CYCLES > 0 stops after that many void increments (for a rate measurement).
// Prints per phase: wall time, DEM steps, particle-steps/s, steps and seconds per cycle.
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <string>

#include "memory_report.hpp"
#include "packlab/core/thread_wait.hpp"
#include "packlab/generate/vem.hpp"

using namespace packlab;

int main(int argc, char** argv) {
  ensure_passive_thread_wait(argv);  // as the packlab program does (core/thread_wait.hpp)
  generate::VemParams p;
  const bool fixed_threads = argc > 1 && std::string(argv[argc - 1]) == "fixed";
  if (fixed_threads) --argc;
  p.adapt_threads = !fixed_threads;
  p.threads = argc > 1 ? std::atoi(argv[1]) : 2;
  if (argc > 2) p.structural = std::atol(argv[2]);
  if (argc > 3) p.voids = std::atol(argv[3]);
  if (argc > 4) p.phi_s = std::atof(argv[4]);
  const long max_cycles = argc > 5 ? std::atol(argv[5]) : 0;
  if (argc > 6) p.skin = std::atof(argv[6]);  // Verlet skin / r_S (results do not depend on it)
  const double particles = static_cast<double>(p.structural + p.voids);

  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  generate::Vem vem(p);
  while (vem.stage() == generate::VemStage::blowup) vem.run(1000);
  const auto t1 = Clock::now();
  const long blowup_steps = vem.total_steps();
  const double blowup_s = std::chrono::duration<double>(t1 - t0).count();
  fmt::print("bench_vem N_S={} N_V={} phi_s={} threads={} ({}) skin={} time_step_rule={} safety={}\n", p.structural,
             p.voids, p.phi_s, p.threads, fixed_threads ? "fixed" : "adaptive", p.skin, p.time_step_rule,
             p.time_step_safety);
  const long blowup_builds = vem.engine().neighbor_builds();
  const long blowup_refreshes = vem.engine().near_list_refreshes();
  fmt::print("blow-up: {} steps in {:.2f} s, {:.4g} particle-steps/s, {} neighbour builds, mean dt {:.3g} s\n",
             blowup_steps, blowup_s, particles * static_cast<double>(blowup_steps) / blowup_s, blowup_builds,
             vem.engine().time() / static_cast<double>(blowup_steps));
  while (!vem.finished() && (max_cycles <= 0 || vem.cycle() < max_cycles)) vem.run(1000);
  const auto t2 = Clock::now();
  const double expansion_s = std::chrono::duration<double>(t2 - t1).count();
  const long expansion_steps = vem.total_steps() - blowup_steps;
  const long cycles = vem.cycle();
  fmt::print(
      "expansion: {} cycles, {} steps in {:.2f} s, {:.4g} particle-steps/s, {:.0f} steps/cycle, "
      "{:.3f} s/cycle, last q {:.3f}, {} relaxations at the step limit, stop {}\n",
      cycles, expansion_steps, expansion_s, particles * static_cast<double>(expansion_steps) / expansion_s,
      static_cast<double>(expansion_steps) / static_cast<double>(std::max(1L, cycles)),
      expansion_s / static_cast<double>(std::max(1L, cycles)), vem.curve().back().q, vem.limited_relaxations(),
      generate::vem_stop_name(vem.stop_reason()));
  fmt::print("expansion: {} neighbour builds\n", vem.engine().neighbor_builds() - blowup_builds);
  // The near list (dem/near_pairs.cpp) and the particle sorts (dem/resort.cpp), issue #14.
  fmt::print("near list: {} refreshes ({} in the blow-up), {} of {} listed pairs at the end; particles sorted {} times\n",
             vem.engine().near_list_refreshes(), blowup_refreshes, vem.engine().near_pairs(),
             vem.engine().listed_pairs(), vem.engine().particle_resorts());
  fmt::print("total: {:.2f} s, {:.4g} particle-steps/s\n", blowup_s + expansion_s,
             particles * static_cast<double>(vem.total_steps()) / (blowup_s + expansion_s));
  bench::print_engine_memory(vem.engine());  // at the end: the dense packing's listed pairs
  for (std::size_t k = 0; k < vem.curve().size(); k += 10) {
    const auto& r = vem.curve()[k];
    fmt::print("  q {:.3f} cn {:.3f} phi_T {:.4f} E_s {:.3e} E_k {:.3e} steps {} ratio {:.2e}\n", r.q, r.cn,
               r.phi_total, r.strain_energy, r.kinetic_energy, r.steps, r.unbalanced_force_ratio);
  }
  return 0;
}
