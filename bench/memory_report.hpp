// What an engine holds on the heap, by part, per particle (and per listed pair): the lines
// bench_relax and bench_compress print (issue #14: bytes per particle and per bond).
#pragma once

#include <fmt/format.h>

#include "packlab/dem/engine.hpp"

namespace packlab::bench {

inline void print_engine_memory(const dem::Engine& engine) {
  const dem::EngineMemory m = engine.memory();
  const double n = static_cast<double>(engine.particle_count());
  const double pairs = static_cast<double>(engine.listed_pairs());
  const auto per = [](std::size_t bytes, double count) { return count > 0 ? static_cast<double>(bytes) / count : 0.0; };
  fmt::print(
      "engine memory per particle: {:.0f} bytes = particles {:.0f} + neighbour list {:.0f} + listed pairs {:.0f} + "
      "contact history {:.0f} (pairs and walls) + bonds {:.0f} + threads {:.0f}; {:.2f} listed pairs per particle, "
      "{:.0f} bytes each besides their history\n",
      per(m.total(), n), per(m.particles, n), per(m.neighbor_list, n), per(m.listed_pairs, n),
      per(m.contact_history, n), per(m.bonds, n), per(m.threads, n), pairs / n, per(m.listed_pairs, pairs));
}

}  // namespace packlab::bench
