#include "packlab/generate/lattice.hpp"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "packlab/core/error.hpp"
#include "packlab/core/memory.hpp"

namespace packlab::generate {

LatticeType lattice_type_from_name(const std::string& name) {
  if (name == "sc") return LatticeType::sc;
  if (name == "bcc") return LatticeType::bcc;
  if (name == "fcc") return LatticeType::fcc;
  fail_input(fmt::format("lattice type = {}: must be sc, bcc or fcc", name));
}

std::string lattice_type_name(LatticeType type) {
  switch (type) {
    case LatticeType::sc: return "sc";
    case LatticeType::bcc: return "bcc";
    case LatticeType::fcc: return "fcc";
  }
  return "?";
}

double lattice_constant(const LatticeParams& p) {
  const double d = 2.0 * p.radius + p.gap;
  switch (p.type) {
    case LatticeType::sc: return d;
    case LatticeType::bcc: return 2.0 * d / std::sqrt(3.0);
    case LatticeType::fcc: return std::sqrt(2.0) * d;
  }
  return d;
}

Packing make_lattice(const LatticeParams& p) {
  require(p.radius > 0.0 && std::isfinite(p.radius), "radius", p.radius, "> 0 m");
  require(p.gap >= 0.0 && std::isfinite(p.gap), "gap", p.gap, ">= 0 m");
  for (int a = 0; a < 3; ++a)
    require(p.cells[a] >= 1 && p.cells[a] <= 1000, fmt::format("cells[{}]", "xyz"[a]), p.cells[a],
            "an integer in [1, 1000]");
  std::vector<Vec3> basis;
  switch (p.type) {
    case LatticeType::sc: basis = {{0, 0, 0}}; break;
    case LatticeType::bcc: basis = {{0, 0, 0}, {0.5, 0.5, 0.5}}; break;
    case LatticeType::fcc: basis = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}}; break;
  }
  // A packing costs at least position, radius, type and flags per sphere (~64 bytes).
  require_memory("cells", static_cast<double>(p.cells[0]) * p.cells[1] * p.cells[2],
                 static_cast<double>(p.cells[0]) * p.cells[1] * p.cells[2] * static_cast<double>(basis.size()), 64.0);
  const double a = lattice_constant(p);
  Packing packing;
  packing.box.lo = {0, 0, 0};
  packing.box.length = {a * p.cells[0], a * p.cells[1], a * p.cells[2]};
  packing.box.periodic = {true, true, true};
  // Shift by a quarter cell so no centre sits on a box face (wrapping is then exact).
  const Vec3 offset{0.25 * a, 0.25 * a, 0.25 * a};
  for (int k = 0; k < p.cells[2]; ++k)
    for (int j = 0; j < p.cells[1]; ++j)
      for (int i = 0; i < p.cells[0]; ++i)
        for (const Vec3& b : basis)
          packing.add(Vec3{(i + b.x) * a, (j + b.y) * a, (k + b.z) * a} + offset, p.radius);
  return packing;
}

}  // namespace packlab::generate
