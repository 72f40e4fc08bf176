// Plane walls: a sphere bouncing off a wall, the impulse the wall records, a moving wall.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "packlab/core/error.hpp"
#include "packlab/dem/engine.hpp"

using namespace packlab;
using namespace packlab::dem;

namespace {

Packing one_sphere(Vec3 position, Vec3 velocity) {
  Packing p;
  p.box.length = {10, 10, 10};
  p.box.periodic = {true, true, false};
  p.add(position, 0.5);
  p.velocity = {velocity};
  return p;
}

EngineConfig linear_config(double damping = 0.0) {
  EngineConfig c;
  c.types = {Material{1000.0, 100.0, 0.3, 1000.0, damping}};
  c.stiffness_rule = StiffnessRule::contact;
  c.threads = 1;
  c.time_step_safety = 0.01;
  return c;
}

}  // namespace

TEST(Walls, SphereBouncesElasticallyAndTheWallRecordsTheImpulse) {
  // Falling on the floor z = 1 at 0.1 m/s: contact time pi sqrt(m/k), restitution 1, and the
  // wall's force integrated over the contact equals the momentum change 2 m v.
  Engine e(one_sphere({5, 5, 1.5005}, {0, 0, -0.1}), linear_config());
  e.add_wall(Wall{{0, 0, 1.0}, {0, 0, 1}, {}});
  const double m = 1000.0 * 4.0 / 3.0 * std::numbers::pi * 0.125;
  double impulse = 0.0;
  long in_contact = 0;
  bool touched = false;
  for (long s = 0; s < 1'000'000; ++s) {
    e.run(1);
    const Vec3 f = e.wall_force(0);
    if (f.z != 0.0) {
      touched = true;
      ++in_contact;
      impulse += f.z * e.time_step();
    } else if (touched) {
      break;
    }
  }
  const Packing out = e.packing();
  EXPECT_NEAR(out.velocity[0].z, 0.1, 1e-6);
  EXPECT_NEAR(static_cast<double>(in_contact) * e.time_step(), std::numbers::pi * std::sqrt(m / 1000.0),
              2 * e.time_step());
  // The particles push the floor down: the recorded force is negative along z.
  EXPECT_NEAR(impulse, -2 * m * 0.1, 1e-3 * 2 * m * 0.1);
}

TEST(Walls, DescendingCeilingSqueezesASphereAgainstTheFloor) {
  // Floor at z = 1, ceiling at z = 2 moving down slowly; the sphere (touching both) is
  // squeezed quasi-statically: both contacts carry k delta/2 for a total approach delta, and
  // the two walls feel equal and opposite forces.
  Engine e(one_sphere({5, 5, 1.5}, {0, 0, 0}), linear_config(0.7));
  const std::size_t floor = e.add_wall(Wall{{0, 0, 1.0}, {0, 0, 1}, {}});
  const double speed = 1e-4;
  const std::size_t ceiling = e.add_wall(Wall{{0, 0, 2.0}, {0, 0, -1}, {0, 0, -speed}});
  e.run(40000);
  const double delta = 2.0 - e.wall(ceiling).point.z;
  EXPECT_NEAR(delta, speed * e.time(), 1e-9 * delta);  // 40000 additions of v dt: round-off
  EXPECT_NEAR(e.wall_force(floor).z, -1000.0 * delta / 2, 0.02 * 1000.0 * delta / 2);
  EXPECT_NEAR(e.wall_force(ceiling).z, 1000.0 * delta / 2, 0.02 * 1000.0 * delta / 2);
  EXPECT_NEAR(e.packing().position[0].z, 1.5 - delta / 2, 0.02 * delta);
}

TEST(Walls, RejectsADegenerateNormal) {
  Engine e(one_sphere({5, 5, 5}, {0, 0, 0}), linear_config());
  EXPECT_THROW(e.add_wall(Wall{{0, 0, 0}, {0, 0, 0}, {}}), InputError);
}
