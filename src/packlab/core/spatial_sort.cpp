#include "packlab/core/spatial_sort.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace packlab {

namespace {

// Spreads the low 21 bits of v so that two zero bits separate each (for 3D interleaving).
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

}  // namespace

std::vector<int> spatial_order(const Box& box, const std::vector<Vec3>& position, double cell_size) {
  const std::size_t n = position.size();
  Vec3 lo = box.lo;
  // Open axes: particles may be outside the box; take their extent.
  for (int a = 0; a < 3; ++a)
    if (!box.periodic[a])
      for (const auto& p : position) lo[a] = std::min(lo[a], p[a]);
  std::vector<std::uint64_t> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = box.wrap(position[i]);
    std::uint64_t code = 0;
    for (int a = 0; a < 3; ++a) {
      const double c = std::floor((p[a] - lo[a]) / cell_size);
      const auto cell = static_cast<std::uint64_t>(std::clamp(c, 0.0, 2097151.0));
      code |= spread_bits(cell) << a;
    }
    key[i] = code;
  }
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  return order;
}

}  // namespace packlab
