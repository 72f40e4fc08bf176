// Compression test of an inverse opal of about 50,000 particles (bpm-inverse-opals):
// particle-steps and bond-steps per second of the DEM engine under load (glued plate moving at
// the automatic quasi-static rate, bonds deforming), and the memory per particle and per bond
// (heap bytes the engine allocates, from glibc's mallinfo2: an engine with the bonds minus one
// without, divided by the bonds; the one without, divided by the particles).
// usage: bench_compress [THREADS] [FILE] [TILES] [STEPS] [fixed]
//   FILE: a bonded model (e.g. `packlab build opal` output, used as it is) or a particle packing
//   (no bonds: tiled TILES x TILES along x, y and made into the opal below); "-" or none: a
//   force-biased packing of 15 nm particles (porosity 0.38, periodic x, y) in the 300 x 259.8 x
//   413 nm box of docs/opal.md, tiled 4 x 4 (about 186,000 particles), made into the FCC opal of
//   docs/opal.md (pores 138 nm at 150 nm spacing, [111] along z, porosity 0.75, two substrate
//   layers, bonds within 1.75 d): about 54,000 particles. STEPS (default 2000) are timed after
//   200 warm-up steps. "fixed": the engine keeps THREADS (EngineConfig::adapt_threads off; by
//   default it starts at one thread and goes up when probes find more faster, docs/engine.md).
// last line: packlab compress N=... bonds=... threads=... pts_per_s=... bond_steps_per_s=... bytes_per_particle=...
// bytes_per_bond=...
#include <fmt/format.h>
#include <malloc.h>

#include <chrono>
#include <cstdlib>
#include <string>

#include "memory_report.hpp"
#include "opal_case.hpp"
#include "packlab/core/thread_wait.hpp"
#include "packlab/mechanics/opal_materials.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"

using namespace packlab;
using namespace packlab::bench;

int main(int argc, char** argv) {
  ensure_passive_thread_wait(argv);  // as the packlab program does (core/thread_wait.hpp)
  const int threads = argc > 1 ? std::atoi(argv[1]) : 1;
  const std::string file = argc > 2 ? argv[2] : "-";
  const int tiles = argc > 3 ? std::atoi(argv[3]) : 4;
  const long steps = argc > 4 ? std::atol(argv[4]) : 2000;
  const bool fixed_threads = argc > 5 && std::string(argv[5]) == "fixed";
  const Packing model = opal_case(file, tiles, threads);

  mechanics::UniaxialCompressionSetup setup;
  setup.options.threads = threads;
  setup.finish(model);
  dem::EngineConfig config = mechanics::compression_engine_config(setup.options);
  config.adapt_threads = !fixed_threads;

  // Memory: an engine with the bonds, and one without.
  Packing bare = model;
  bare.bonds = Bonds{};
  std::size_t bytes_bare = 0, bytes_full = 0;
  {
    const std::size_t h0 = heap_in_use();
    dem::Engine e(bare, config);
    bytes_bare = heap_in_use() - h0;
  }
  const std::size_t h0 = heap_in_use();
  dem::Engine engine(model, config);
  bytes_full = heap_in_use() - h0;
  const double n = static_cast<double>(model.size()), nb = static_cast<double>(model.bonds.size());
  const double per_particle = static_cast<double>(bytes_bare) / n;
  const double per_bond = (static_cast<double>(bytes_full) - static_cast<double>(bytes_bare)) / nb;

  // The compression set-up: substrate fixed (from the model), plate on top moving at the
  // automatic quasi-static rate.
  double top = -1e300, bottom = 1e300;
  for (std::size_t k = 0; k < model.size(); ++k) {
    top = std::max(top, model.position[k].z + model.radius[k]);
    bottom = std::min(bottom, model.position[k].z - model.radius[k]);
  }
  engine.add_wall(dem::Wall{{0, 0, top}, {0, 0, -1}, {0, 0, -setup.options.strain_rate * (top - bottom)}});
  engine.run(200);
  const auto t0 = std::chrono::steady_clock::now();
  engine.run(steps);
  const double seconds = since(t0);
  const double pts = n * static_cast<double>(steps) / seconds;
  const double bts = nb * static_cast<double>(steps) / seconds;
  fmt::print(
      "{} particles, {} bonds, {} threads ({}; {} at the end, {} switches): {} steps in {:.2f} s (time step "
      "{:.3g} s)\n",
      model.size(), model.bonds.size(), threads, fixed_threads ? "fixed" : "adaptive", engine.active_threads(),
      engine.thread_switches(), steps, seconds, engine.time_step());
  fmt::print("memory: {:.0f} bytes per particle (engine without bonds: {:.1f} MB), {:.0f} bytes per bond\n",
             per_particle, static_cast<double>(bytes_bare) * 1e-6, per_bond);
  print_engine_memory(engine);  // after the run: with the plate's wall history and the step's sums
  fmt::print(
      "packlab compress N={} bonds={} threads={} pts_per_s={:.4g} bond_steps_per_s={:.4g} bytes_per_particle={:.0f} "
      "bytes_per_bond={:.0f}\n",
      model.size(), model.bonds.size(), threads, pts, bts, per_particle, per_bond);
  return 0;
}
