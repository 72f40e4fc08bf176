#include "packlab/generate/overlap_check.hpp"

#include <algorithm>
#include <vector>

#include "packlab/core/neighbor_list.hpp"

namespace packlab::generate {

double min_contact_ratio(const Packing& packing) {
  std::vector<Vec3> position = packing.position;
  NeighborList list(0.0);
  list.build(packing.box, position, packing.radius);
  double ratio = 1.0;
  for (int i = 0; i < static_cast<int>(packing.size()); ++i) {
    for (int p = list.first(i); p < list.first(i + 1); ++p) {
      const int j = list.partner()[p];
      const Vec3 d = position[j] + list.image_offset(list.image()[p]) - position[i];
      ratio = std::min(ratio, norm(d) / (packing.radius[i] + packing.radius[j]));
    }
  }
  return ratio;
}

}  // namespace packlab::generate
