#include "packlab/generate/random.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "packlab/core/error.hpp"
#include "packlab/core/memory.hpp"

namespace packlab::generate {

double cube_edge(long particles, double radius, double volume_fraction) {
  const double v = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  return std::cbrt(static_cast<double>(particles) * v / volume_fraction);
}

Packing make_random_packing(const RandomPackingParams& p, Random& rng) {
  require(p.particles >= 1 && p.particles <= 100'000'000, "particles", static_cast<double>(p.particles),
          "in [1, 1e8]");
  require(p.radius > 0.0 && std::isfinite(p.radius), "radius", p.radius, "> 0 m");
  require_memory("particles", static_cast<double>(p.particles), static_cast<double>(p.particles), 64.0);
  const double max_phi = p.allow_overlap ? 1.0 : rsa_max_volume_fraction;
  require(p.volume_fraction > 0.0 && p.volume_fraction < max_phi, "volume_fraction", p.volume_fraction,
          p.allow_overlap ? std::string("in (0, 1)")
                          : fmt::format("in (0, {}) without overlaps (random sequential addition jams near 0.38)",
                                        rsa_max_volume_fraction));
  for (int a = 0; a < 3; ++a) require(p.aspect[a] > 0.0, "aspect", p.aspect[a], "> 0");
  const double volume = static_cast<double>(p.particles) * 4.0 / 3.0 * std::numbers::pi * p.radius * p.radius *
                        p.radius / p.volume_fraction;
  const double scale = std::cbrt(volume / (p.aspect[0] * p.aspect[1] * p.aspect[2]));
  Packing packing;
  packing.box.length = {p.aspect[0] * scale, p.aspect[1] * scale, p.aspect[2] * scale};
  packing.box.periodic = p.periodic;
  for (int a = 0; a < 3; ++a)
    if (packing.box.length[a] < 2.0 * p.radius)
      fail_input(fmt::format("box edge along {} = {:g} m is smaller than a particle diameter; use more particles",
                             "xyz"[a], packing.box.length[a]));
  auto draw = [&] {
    Vec3 c;
    for (int a = 0; a < 3; ++a) {
      // Open axes keep whole spheres inside the box.
      const double margin = p.periodic[a] ? 0.0 : p.radius;
      c[a] = rng.uniform(margin, packing.box.length[a] - margin);
    }
    return c;
  };
  if (p.allow_overlap) {
    for (long k = 0; k < p.particles; ++k) packing.add(draw(), p.radius);
    return packing;
  }
  // RSA with a uniform grid of cells of edge >= one diameter for the overlap test.
  std::array<int, 3> nc;
  for (int a = 0; a < 3; ++a) nc[a] = std::max(1, static_cast<int>(packing.box.length[a] / (2.0 * p.radius)));
  std::vector<std::vector<int>> cells(static_cast<std::size_t>(nc[0]) * nc[1] * nc[2]);
  auto cell_of = [&](const Vec3& c, int a) {
    return std::min(nc[a] - 1, static_cast<int>(c[a] / packing.box.length[a] * nc[a]));
  };
  const long max_attempts = 1000 * p.particles + 100000;
  long attempts = 0;
  while (static_cast<long>(packing.size()) < p.particles) {
    if (++attempts > max_attempts)
      fail_input(fmt::format("volume_fraction = {:g}: random sequential addition placed only {} of {} spheres "
                             "in {} attempts; lower it",
                             p.volume_fraction, packing.size(), p.particles, max_attempts));
    const Vec3 c = draw();
    const int ci[3] = {cell_of(c, 0), cell_of(c, 1), cell_of(c, 2)};
    bool free = true;
    for (int dz = -1; dz <= 1 && free; ++dz)
      for (int dy = -1; dy <= 1 && free; ++dy)
        for (int dx = -1; dx <= 1 && free; ++dx) {
          int k[3] = {ci[0] + dx, ci[1] + dy, ci[2] + dz};
          bool skip = false;
          for (int a = 0; a < 3; ++a) {
            if (k[a] < 0 || k[a] >= nc[a]) {
              if (!p.periodic[a]) skip = true;
              k[a] = (k[a] + nc[a]) % nc[a];
            }
          }
          if (skip) continue;
          for (int other : cells[k[0] + nc[0] * (k[1] + nc[1] * k[2])]) {
            const Vec3 d = packing.box.minimum_image(packing.position[other] - c);
            if (norm2(d) < 4.0 * p.radius * p.radius) {
              free = false;
              break;
            }
          }
        }
    if (!free) continue;
    cells[ci[0] + nc[0] * (ci[1] + nc[1] * ci[2])].push_back(static_cast<int>(packing.size()));
    packing.add(c, p.radius);
  }
  return packing;
}

}  // namespace packlab::generate
