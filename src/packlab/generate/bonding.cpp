#include "packlab/generate/bonding.hpp"

#include <cmath>

#include "packlab/analyze/coordination.hpp"
#include "packlab/core/error.hpp"

namespace packlab::generate {

double bonding_cutoff_ratio(const std::string& model, double eps, double elastic_cutoff) {
  if (model == "contact") {
    require(eps >= 0.0 && eps < 1.0, "eps", eps, "in [0, 1)");
    return 1.0 + eps;
  }
  if (model == "elastic") {
    require(elastic_cutoff >= 1.0 && elastic_cutoff < 2.0, "cutoff_ratio", elastic_cutoff, "in [1, 2)");
    return elastic_cutoff;
  }
  fail_input("model = " + model + ": must be contact or elastic");
}

void add_bonds(Packing& packing, const BondingOptions& options) {
  require(options.cutoff_ratio >= 1.0 && options.cutoff_ratio < 2.0, "cutoff_ratio", options.cutoff_ratio,
          "in [1, 2)");
  // find_contacts lists every pair with d < (1 + eps)(r_i + r_j), each once, images included.
  const analyze::ContactList pairs = analyze::find_contacts(packing, options.cutoff_ratio - 1.0, options.threads);
  const Box& box = packing.box;
  Bonds bonds;
  for (std::size_t c = 0; c < pairs.size(); ++c) {
    const int i = pairs.i[c], j = pairs.j[c];
    const int material =
        options.material_of_types ? options.material_of_types(packing.type[i], packing.type[j]) : 0;
    if (material < 0) continue;
    // The image of j: the branch vector is r_j + image L - r_i.
    const Vec3 shift = packing.position[i] + pairs.branch[c] - packing.position[j];
    std::array<int, 3> image{};
    for (int a = 0; a < 3; ++a)
      image[a] = box.periodic[a] ? static_cast<int>(std::lround(shift[a] / box.length[a])) : 0;
    bonds.add(i, j, image, material, norm(pairs.branch[c]));
  }
  packing.bonds = std::move(bonds);
}

}  // namespace packlab::generate
