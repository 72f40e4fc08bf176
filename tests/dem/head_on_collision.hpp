// Two spheres colliding head-on along x in a big open box: the contact time and the coefficient
// of restitution the engine gives, for the contact-law tests to check against theory.
#pragma once

#include "packlab/core/packing.hpp"
#include "packlab/dem/engine.hpp"

namespace packlab::test {

// Two spheres on the x axis approaching head-on with speed v each, in a big open box.
inline Packing head_on_pair(double radius, double speed, double gap) {
  Packing p;
  p.box.lo = {-10 * radius, -10 * radius, -10 * radius};
  p.box.length = {20 * radius, 20 * radius, 20 * radius};
  p.box.periodic = {false, false, false};
  p.add({-radius - 0.5 * gap, 0, 0}, radius);
  p.add({radius + 0.5 * gap, 0, 0}, radius);
  p.velocity = {{speed, 0, 0}, {-speed, 0, 0}};
  return p;
}

struct Collision {
  double duration;     // time in contact [s]
  double restitution;  // separation speed / approach speed
};

// Runs the pair with time step dt, one thread, until the spheres have touched and come apart.
inline Collision collide(const Packing& start, dem::EngineConfig config, double dt) {
  config.time_step = dt;
  config.threads = 1;
  dem::Engine engine(start, config);
  const double v0 = start.velocity[1].x - start.velocity[0].x;
  long in_contact = 0;
  bool touched = false;
  for (long s = 0; s < 10'000'000; ++s) {
    const auto x = engine.packing().position;
    const double overlap = 2 * start.radius[0] - (x[1].x - x[0].x);
    if (overlap > 0) {
      touched = true;
      ++in_contact;
    } else if (touched) {
      break;
    }
    engine.run(1);
  }
  const auto v = engine.packing().velocity;
  return {static_cast<double>(in_contact) * dt, (v[1].x - v[0].x) / -v0};
}

}  // namespace packlab::test
