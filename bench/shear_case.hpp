// The shear benchmarks' structure (bench_shear, bench_static shear): the VEM packing in `file`
// (default: the N_S = 8000 structure of docs/shear.md), contact bonds at 1.01 x 2r added when the
// file has none.
#pragma once

#include <string>

#include "packlab/core/packing.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::bench {

inline Packing shear_case(const std::string& file) {
  Packing packing = io::read_packing(file);
  if (packing.bonds.empty()) {
    generate::BondingOptions bo;
    bo.cutoff_ratio = 1.01;
    generate::add_bonds(packing, bo);
  }
  return packing;
}

}  // namespace packlab::bench
