// Cundall's local non-viscous damping (vem-void-expansion-method §2.1, after Cundall 1987):
// F_d,k = -alpha |F_k| sign(v_k) per component. It is proportional to the unbalanced force,
// so it damps accelerating motion only and vanishes at equilibrium; the same form damps
// moments with the angular velocity.
#pragma once

#include <cmath>

#include "packlab/core/vec3.hpp"

namespace packlab::dem {

// sign(v) with sign(0) = 0, written branch-free so the integration loop vectorizes.
inline double sign(double v) { return static_cast<double>(v > 0.0) - static_cast<double>(v < 0.0); }

// Returns the damped force F + F_d.
inline Vec3 apply_local_damping(const Vec3& force, const Vec3& velocity, double alpha) {
  return {force.x - alpha * std::abs(force.x) * sign(velocity.x),
          force.y - alpha * std::abs(force.y) * sign(velocity.y),
          force.z - alpha * std::abs(force.z) * sign(velocity.z)};
}

}  // namespace packlab::dem
