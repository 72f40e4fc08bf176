// Neighbour-list build rate (linked cells + Verlet list, core/neighbor_list): a random periodic
// packing like the void expansion method's early stages (N_S spheres of radius 1 at volume
// fraction PHI_S plus N_V tiny ones of radius 0.005), skin 0.2.
// usage: bench_neighbor [N_S] [N_V] [PHI_S] [BUILDS] [THREADS]
// Prints ms per build, particles per second and pairs listed.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "packlab/core/neighbor_list.hpp"
#include "packlab/core/random.hpp"
#include "packlab/core/thread_wait.hpp"

using namespace packlab;

int main(int argc, char** argv) {
  ensure_passive_thread_wait(argv);  // as the packlab program does (core/thread_wait.hpp)
  const long structural = argc > 1 ? std::atol(argv[1]) : 8000;
  const long voids = argc > 2 ? std::atol(argv[2]) : 2000;
  const double phi = argc > 3 ? std::atof(argv[3]) : 0.4;
  const int builds = argc > 4 ? std::atoi(argv[4]) : 200;
  const int threads = argc > 5 ? std::atoi(argv[5]) : 1;
  const double edge = std::cbrt(4.0 * std::numbers::pi * static_cast<double>(structural) / (3.0 * phi));
  Box box;
  box.length = {edge, edge, edge};
  box.periodic = {true, true, true};
  Random rng(1);
  std::vector<Vec3> position;
  std::vector<double> radius;
  for (long i = 0; i < structural + voids; ++i) {
    position.push_back({rng.uniform(0.0, edge), rng.uniform(0.0, edge), rng.uniform(0.0, edge)});
    radius.push_back(i < structural ? 1.0 : 0.005);
  }
  NeighborList list(0.2);
  list.build(box, position, radius, threads);
  // Small random moves between builds, as in a run (the list keeps the last one for history).
  const auto t0 = std::chrono::steady_clock::now();
  for (int b = 0; b < builds; ++b) {
    for (auto& p : position) p += 0.01 * rng.unit_vector();
    list.build(box, position, radius, threads);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double n = static_cast<double>(position.size());
  fmt::print("bench_neighbor N={} phi_s={} threads={}: {:.3f} ms per build, {:.3g} particles/s, {} pairs listed\n",
             position.size(), phi, threads, 1e3 * s / builds, n * builds / s, list.pair_count());
  return 0;
}
