// Plane walls: adding one (its contact histories laid out per particle) and the geometry the
// contact law sees for a particle against it. The wall loop is in step.cpp.
#include <cmath>

#include "packlab/core/error.hpp"
#include "packlab/dem/engine.hpp"

namespace packlab::dem {

std::size_t Engine::add_wall(const Wall& wall) {
  const double length = norm(wall.normal);
  if (!(length > 0.0) || !std::isfinite(length)) fail_input("wall normal: must be a nonzero finite vector");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(wall.point[a]) || !std::isfinite(wall.velocity[a]))
      fail_input("wall point and velocity: must be finite");
  Wall w = wall;
  w.normal *= 1.0 / length;
  // Re-layout the per-particle wall histories for one more wall.
  const std::size_t n = particles_.size(), walls = walls_.size();
  std::visit(
      [&](auto& model) {
        std::decay_t<decltype(model.wall_history)> history(n * (walls + 1));
        for (std::size_t k = 0; k < n; ++k)
          for (std::size_t m = 0; m < walls; ++m) history[k * (walls + 1) + m] = model.wall_history[k * walls + m];
        model.wall_history.swap(history);
      },
      model_);
  walls_.push_back(w);
  wall_force_.push_back(Vec3{});
  return walls_.size() - 1;
}

ContactGeometry Engine::wall_geometry(std::size_t k, const Wall& wall, double distance) const {
  const auto& P = particles_;
  // The particle is i, the wall j: the normal points from the particle into the wall.
  ContactGeometry g;
  g.normal = -wall.normal;
  g.overlap = P.radius[k] - distance;
  g.branch_i = distance;
  g.branch_j = 0.0;
  g.relative_velocity = wall.velocity - P.velocity[k] - cross(g.branch_i * P.angular_velocity[k], g.normal);
  g.mean_spin = 0.5 * P.angular_velocity[k];
  g.dt = dt_;
  g.radius_i = P.radius[k];
  g.radius_j = 1e12 * P.radius[k];  // a plane: R* = r
  g.effective_mass = P.mass[k];
  g.spin_i = P.angular_velocity[k];
  g.spin_j = Vec3{};
  g.time = time_;
  return g;
}

}  // namespace packlab::dem
