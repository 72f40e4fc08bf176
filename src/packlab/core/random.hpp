// The one random generator: a seeded 64-bit Mersenne twister passed explicitly by reference
// to every algorithm that draws (no global state). Same seed, inputs and thread count give
// the same result.
#pragma once

#include <cstdint>
#include <random>

#include "packlab/core/vec3.hpp"

namespace packlab {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  // Uniform on [0, 1).
  double uniform() { return std::generate_canonical<double, 53>(engine_); }
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  std::uint64_t next() { return engine_(); }
  // Uniform integer on [0, n).
  std::uint64_t below(std::uint64_t n) { return std::uniform_int_distribution<std::uint64_t>(0, n - 1)(engine_); }
  double normal() { return std::normal_distribution<double>(0.0, 1.0)(engine_); }
  // Uniformly distributed unit vector (Marsaglia's method through normals).
  Vec3 unit_vector() {
    for (;;) {
      const Vec3 v{normal(), normal(), normal()};
      const double n = norm(v);
      if (n > 1e-12) return v * (1.0 / n);
    }
  }

  std::mt19937_64& engine() { return engine_; }
  const std::mt19937_64& engine() const { return engine_; }

 private:
  std::mt19937_64 engine_;
};

}  // namespace packlab
