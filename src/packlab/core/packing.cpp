#include "packlab/core/packing.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <unordered_map>

#include "packlab/core/error.hpp"

namespace packlab {

double Packing::volume_fraction() const {
  double v = 0.0;
  for (double r : radius) v += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return v / box.volume();
}

void Packing::validate() const {
  const std::size_t n = size();
  auto check_size = [n](std::size_t got, const char* name, bool optional) {
    if (got == n || (optional && got == 0)) return;
    fail_input(fmt::format("{} has {} entries but the packing has {} particles", name, got, n));
  };
  check_size(radius.size(), "radius", false);
  check_size(type.size(), "type", false);
  check_size(velocity.size(), "velocity", true);
  check_size(angular_velocity.size(), "angular_velocity", true);
  check_size(density.size(), "density", true);
  check_size(fixed.size(), "fixed", true);
  for (const auto& f : fields) check_size(f.values.size(), f.name.c_str(), false);
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(box.lo[a]))
      fail_input(fmt::format("box lo along {} = {:g}: must be finite", "xyz"[a], box.lo[a]));
    if (!(box.length[a] > 0.0) || !std::isfinite(box.length[a]))
      fail_input(fmt::format("box length along {} = {:g}: must be positive and finite", "xyz"[a],
                             box.length[a]));
  }
  auto finite = [](const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  for (std::size_t k = 0; k < n; ++k) {
    if (!(radius[k] > 0.0) || !std::isfinite(radius[k]))
      fail_input(fmt::format("radius of particle {} = {:g}: must be positive and finite", k, radius[k]));
    const Vec3& p = position[k];
    if (!finite(p))
      fail_input(fmt::format("position of particle {} = ({:g}, {:g}, {:g}): must be finite", k, p.x, p.y, p.z));
    if (type[k] < 0) fail_input(fmt::format("type of particle {} = {}: must be >= 0", k, type[k]));
    if (!velocity.empty() && !finite(velocity[k]))
      fail_input(fmt::format("velocity of particle {} = ({:g}, {:g}, {:g}): must be finite", k, velocity[k].x,
                             velocity[k].y, velocity[k].z));
    if (!angular_velocity.empty() && !finite(angular_velocity[k]))
      fail_input(fmt::format("angular velocity of particle {} = ({:g}, {:g}, {:g}): must be finite", k,
                             angular_velocity[k].x, angular_velocity[k].y, angular_velocity[k].z));
    if (!density.empty() && (!(density[k] > 0.0) || !std::isfinite(density[k])))
      fail_input(fmt::format("density of particle {} = {:g}: must be positive and finite", k, density[k]));
  }
  validate_bonds();
}

void Packing::validate_bonds() const {
  const std::size_t n = size();
  const std::size_t nb = bonds.size();
  if (bonds.j.size() != nb || bonds.image.size() != nb || bonds.material.size() != nb ||
      bonds.rest_length.size() != nb || bonds.state.size() != nb)
    fail_input("bond arrays have different lengths");
  // Each bond under one key, whichever end it was written from: (i, j, s) and (j, i, -s) are the
  // same bond, since r_j + s L - r_i = -(r_i - s L - r_j).
  struct Key {
    int i, j;
    std::array<int, 3> image;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 1469598103934665603ull;
      for (const int v : {k.i, k.j, k.image[0], k.image[1], k.image[2]})
        h = (h ^ static_cast<std::uint32_t>(v)) * 1099511628211ull;
      return static_cast<std::size_t>(h);
    }
  };
  std::unordered_map<Key, std::size_t, KeyHash> first_bond;
  first_bond.reserve(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    const int bi = bonds.i[b], bj = bonds.j[b];
    const auto& s = bonds.image[b];
    if (bi < 0 || bj < 0 || static_cast<std::size_t>(bi) >= n || static_cast<std::size_t>(bj) >= n)
      fail_input(fmt::format("bond {} joins particles {} and {}: indices must be in [0, {})", b, bi, bj, n));
    // A bond to the particle's own periodic image has a length (|s L|) and is kept; one to the
    // particle itself has none, so its direction and strain are 0/0.
    if (bi == bj && s == std::array<int, 3>{0, 0, 0})
      fail_input(fmt::format("bond {} joins particle {} to itself (image 0 0 0): a bond needs two particles", b,
                             bi));
    if (!std::isfinite(bonds.rest_length[b]) || bonds.rest_length[b] < 0.0)
      fail_input(fmt::format("rest length of bond {} = {:g}: must be finite and >= 0", b, bonds.rest_length[b]));
    const bool forward = bi < bj || (bi == bj && s > std::array<int, 3>{-s[0], -s[1], -s[2]});
    const Key key = forward ? Key{bi, bj, s} : Key{bj, bi, {-s[0], -s[1], -s[2]}};
    const auto [at, inserted] = first_bond.emplace(key, b);
    if (!inserted)
      fail_input(fmt::format("bonds {} and {} both join particles {} and {} (image {} {} {}): a pair is bonded "
                             "at most once",
                             at->second, b, bi, bj, s[0], s[1], s[2]));
  }
}

const ScalarField* Packing::field(const std::string& name) const {
  for (const auto& f : fields)
    if (f.name == name) return &f;
  return nullptr;
}

ScalarField& Packing::field_or_add(const std::string& name) {
  for (auto& f : fields)
    if (f.name == name) return f;
  fields.push_back({name, std::vector<double>(size(), 0.0)});
  return fields.back();
}

}  // namespace packlab
