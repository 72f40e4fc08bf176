// The simulation box: an axis-aligned cuboid [lo, lo + length), periodic or not per axis.
#pragma once

#include <array>
#include <cmath>

#include "packlab/core/vec3.hpp"

namespace packlab {

struct Box {
  Vec3 lo{0.0, 0.0, 0.0};
  Vec3 length{1.0, 1.0, 1.0};
  std::array<bool, 3> periodic{true, true, true};

  double volume() const { return length.x * length.y * length.z; }
  Vec3 hi() const { return lo + length; }
  bool any_periodic() const { return periodic[0] || periodic[1] || periodic[2]; }

  // Shortest periodic image of the separation d = r_j - r_i (unchanged along open axes).
  Vec3 minimum_image(Vec3 d) const {
    for (int a = 0; a < 3; ++a)
      if (periodic[a]) d[a] -= length[a] * std::nearbyint(d[a] / length[a]);
    return d;
  }

  // Integer number of box lengths by which the minimum image shifted d (d_min = d + shift*L).
  std::array<int, 3> image_shift(const Vec3& d) const {
    std::array<int, 3> s{0, 0, 0};
    for (int a = 0; a < 3; ++a)
      if (periodic[a]) s[a] = -static_cast<int>(std::nearbyint(d[a] / length[a]));
    return s;
  }

  // Displacement of the periodic image `image` (in box lengths).
  Vec3 shift_vector(const std::array<int, 3>& image) const {
    return {image[0] * length.x, image[1] * length.y, image[2] * length.z};
  }

  // Maps p into [lo, lo + length) along periodic axes; `image` (optional) counts the wraps.
  Vec3 wrap(Vec3 p, std::array<int, 3>* image = nullptr) const {
    for (int a = 0; a < 3; ++a) {
      if (!periodic[a]) continue;
      double n = std::floor((p[a] - lo[a]) / length[a]);
      // A run gone non-finite (the engine stops it at its next measured step) or flung beyond
      // int range must not reach the integer cast below (undefined behaviour).
      if (!(std::abs(n) < 1e9)) continue;
      p[a] -= n * length[a];
      // floor can land exactly on hi after round-off; keep the half-open interval (and count
      // that wrap too: the image it adds is real).
      if (p[a] >= lo[a] + length[a]) {
        p[a] -= length[a];
        n += 1.0;
      }
      if (p[a] < lo[a]) p[a] = lo[a];
      if (image) (*image)[a] += static_cast<int>(n);
    }
    return p;
  }
};

}  // namespace packlab
