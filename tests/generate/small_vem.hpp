// Small, fast void expansion runs for the tests: a few structural particles of radius 1, voids
// grown by 0.05 r_S per cycle, short relaxations, one thread.
#pragma once

#include "packlab/generate/vem.hpp"

namespace packlab::test {

inline generate::VemParams small_vem(long structural, long voids, double phi_s, double max_q, long relax_max_steps) {
  generate::VemParams p;
  p.structural = structural;
  p.voids = voids;
  p.phi_s = phi_s;
  p.void_radius_ratio = 0.05;
  p.max_q = max_q;
  p.relax_max_steps = relax_max_steps;
  p.threads = 1;
  return p;
}

}  // namespace packlab::test
