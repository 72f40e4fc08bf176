// Particle state of a running simulation as contiguous arrays (one entry per particle).
#pragma once

#include <cstdint>
#include <vector>

#include "packlab/core/vec3.hpp"

namespace packlab {

// Moment of inertia of a solid sphere [kg m^2].
inline double sphere_inertia(double mass, double radius) { return 0.4 * mass * radius * radius; }

struct ParticleStore {
  std::vector<Vec3> position;          // [m]
  std::vector<Vec3> velocity;          // [m/s]  (half-step velocity of the leap-frog scheme)
  std::vector<Vec3> angular_velocity;  // [rad/s]
  std::vector<Vec3> force;             // [N]
  std::vector<Vec3> torque;            // [N m]
  std::vector<double> radius;          // [m]
  std::vector<double> mass;            // [kg]
  std::vector<double> inverse_mass;    // 0 for fixed particles
  // 1 / sphere_inertia(mass, radius), 0 for fixed particles. The moment of inertia itself is
  // not stored (issue #14: bytes per particle).
  std::vector<double> inverse_inertia;
  std::vector<int> type;
  std::vector<std::uint8_t> fixed;

  std::size_t size() const { return position.size(); }
  void resize(std::size_t n) {
    position.resize(n);
    velocity.resize(n);
    angular_velocity.resize(n);
    force.resize(n);
    torque.resize(n);
    radius.resize(n);
    mass.resize(n);
    inverse_mass.resize(n);
    inverse_inertia.resize(n);
    type.resize(n);
    fixed.resize(n);
  }
};

}  // namespace packlab
