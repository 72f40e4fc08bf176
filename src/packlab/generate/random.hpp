// Random starting packings:
//  - uniform random centres with overlaps allowed at a nominal volume fraction (the start
//    of the DEM "relax" benchmark and of soft-sphere relaxation);
//  - random sequential addition (RSA): non-overlapping spheres placed one by one, rejecting
//    overlaps, up to a volume fraction below the RSA jamming limit (about 0.38).
#pragma once

#include <array>
#include <cstdint>

#include "packlab/core/packing.hpp"
#include "packlab/core/random.hpp"

namespace packlab::generate {

struct RandomPackingParams {
  long particles = 1000;
  double radius = 0.5;               // [m]
  double volume_fraction = 0.5;      // nominal: sum of sphere volumes / box volume
  std::array<double, 3> aspect{1, 1, 1};  // box edge ratios
  std::array<bool, 3> periodic{true, true, true};
  bool allow_overlap = true;         // false = random sequential addition
};

// Largest volume fraction accepted for RSA (its jamming limit is about 0.384).
inline constexpr double rsa_max_volume_fraction = 0.36;

Packing make_random_packing(const RandomPackingParams& params, Random& rng);

// Box edge of a cube holding `particles` spheres of `radius` at `volume_fraction`.
double cube_edge(long particles, double radius, double volume_fraction);

}  // namespace packlab::generate
