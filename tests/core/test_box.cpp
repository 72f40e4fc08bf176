#include <gtest/gtest.h>

#include "packlab/core/box.hpp"

using packlab::Box;
using packlab::Vec3;

TEST(Box, MinimumImageAlongPeriodicAxesOnly) {
  Box box;
  box.length = {10, 20, 30};
  box.periodic = {true, true, false};
  const Vec3 d = box.minimum_image({9, -11, 29});
  EXPECT_DOUBLE_EQ(d.x, -1);
  EXPECT_DOUBLE_EQ(d.y, 9);
  EXPECT_DOUBLE_EQ(d.z, 29);  // open axis untouched
  const auto s = box.image_shift({9, -11, 29});
  EXPECT_EQ(s[0], -1);
  EXPECT_EQ(s[1], 1);
  EXPECT_EQ(s[2], 0);
  const Vec3 back = Vec3{9, -11, 29} + box.shift_vector(s);
  EXPECT_DOUBLE_EQ(back.x, d.x);
  EXPECT_DOUBLE_EQ(back.y, d.y);
}

TEST(Box, WrapKeepsHalfOpenIntervalAndCountsImages) {
  Box box;
  box.lo = {-1, 0, 0};
  box.length = {2, 1, 1};
  std::array<int, 3> image{0, 0, 0};
  const Vec3 p = box.wrap({3.5, -0.25, 1.0}, &image);
  EXPECT_DOUBLE_EQ(p.x, -0.5);
  EXPECT_DOUBLE_EQ(p.y, 0.75);
  EXPECT_DOUBLE_EQ(p.z, 0.0);  // exactly hi maps to lo
  EXPECT_EQ(image[0], 2);
  EXPECT_EQ(image[1], -1);
  EXPECT_EQ(image[2], 1);
  // Round-off just below lo must not land on hi.
  const Vec3 q = box.wrap({-1.0 - 1e-17, 0.5, 0.5});
  EXPECT_LT(q.x, box.hi().x);
  EXPECT_GE(q.x, box.lo.x);
}
