#include "packlab/core/packing.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

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
  for (int a = 0; a < 3; ++a)
    if (!(box.length[a] > 0.0) || !std::isfinite(box.length[a]))
      fail_input(fmt::format("box length along {} = {:g}: must be positive and finite", "xyz"[a],
                             box.length[a]));
  for (std::size_t k = 0; k < n; ++k) {
    if (!(radius[k] > 0.0) || !std::isfinite(radius[k]))
      fail_input(fmt::format("radius of particle {} = {:g}: must be positive and finite", k, radius[k]));
    const Vec3& p = position[k];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail_input(fmt::format("position of particle {} is not finite", k));
    if (type[k] < 0) fail_input(fmt::format("type of particle {} = {}: must be >= 0", k, type[k]));
    if (!density.empty() && !(density[k] > 0.0))
      fail_input(fmt::format("density of particle {} = {:g}: must be positive", k, density[k]));
  }
  const std::size_t nb = bonds.size();
  if (bonds.j.size() != nb || bonds.image.size() != nb || bonds.material.size() != nb ||
      bonds.rest_length.size() != nb || bonds.state.size() != nb)
    fail_input("bond arrays have different lengths");
  for (std::size_t b = 0; b < nb; ++b) {
    if (bonds.i[b] < 0 || bonds.j[b] < 0 || static_cast<std::size_t>(bonds.i[b]) >= n ||
        static_cast<std::size_t>(bonds.j[b]) >= n)
      fail_input(fmt::format("bond {} joins particles {} and {}: indices must be in [0, {})", b,
                             bonds.i[b], bonds.j[b], n));
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
