// Cundall's local non-viscous damping (vem-void-expansion-method §2.1, after Cundall 1987):
// F_d,k = -alpha |F_k| sign(v_k) per component. It is proportional to the unbalanced force,
// so it damps accelerating motion only and vanishes at equilibrium; the same form damps
// moments with the angular velocity.
#pragma once

#include <cmath>

#include "packlab/core/vec3.hpp"

namespace packlab::dem {

// sign(v) with sign(0) = 0.
inline double sign(double v) { return static_cast<double>(v > 0.0) - static_cast<double>(v < 0.0); }

// One component: f - alpha |f| sign(v). Written with copysign and a 0/1 factor instead of
// comparisons of v: velocity signs are random, and a branch on them mispredicts half the time.
inline double damp_component(double f, double v, double alpha) {
  return f - std::copysign(alpha * std::abs(f), v) * static_cast<double>(v != 0.0);
}

// Returns the damped force F + F_d.
inline Vec3 apply_local_damping(const Vec3& force, const Vec3& velocity, double alpha) {
  return {damp_component(force.x, velocity.x, alpha), damp_component(force.y, velocity.y, alpha),
          damp_component(force.z, velocity.z, alpha)};
}

}  // namespace packlab::dem
