// Orders particles along a Morton (Z-order) curve of cells, so particles that are close in
// space are close in memory: neighbour data then comes from cache instead of main memory.
#pragma once

#include <vector>

#include "packlab/core/box.hpp"
#include "packlab/core/vec3.hpp"

namespace packlab {

// Returns the permutation: order[k] is the index of the particle placed k-th.
// `cell_size` is the edge of the sorting cells (about one interaction range).
std::vector<int> spatial_order(const Box& box, const std::vector<Vec3>& position, double cell_size);

}  // namespace packlab
