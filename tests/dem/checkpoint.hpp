// The checkpoint test shared by the engine's tests: N steps + save + load into a fresh engine +
// N steps must be the 2N steps of an engine run straight, bit for bit.
#pragma once

#include <gtest/gtest.h>

#include <sstream>

#include "packlab/core/packing.hpp"
#include "packlab/dem/engine.hpp"

namespace packlab::test {

inline void expect_checkpoint_continues_bitwise(const Packing& p, const dem::EngineConfig& config, long steps) {
  dem::Engine straight(p, config);
  straight.run(2 * steps);
  dem::Engine first(p, config);
  first.run(steps);
  std::stringstream state;
  first.save_state(state);
  dem::Engine resumed(p, config);
  resumed.load_state(state);
  resumed.run(steps);
  EXPECT_EQ(resumed.step_count(), straight.step_count());
  EXPECT_EQ(resumed.time(), straight.time());
  EXPECT_TRUE(resumed.particles().position == straight.particles().position);
  EXPECT_TRUE(resumed.particles().velocity == straight.particles().velocity);
  EXPECT_TRUE(resumed.particles().angular_velocity == straight.particles().angular_velocity);
}

}  // namespace packlab::test
