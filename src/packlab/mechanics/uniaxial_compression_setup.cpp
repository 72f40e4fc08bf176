// Uniaxial compression: the options and the specimen (opened axes, substrate, glued plate,
// load-bearing bonds, cross-section and gauge height). The loading: uniaxial_compression.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "packlab/core/error.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"

namespace packlab::mechanics {

namespace {

// A: the periodic cross-section Lx Ly, or the x-y extent of the spheres along open sides.
double cross_section_area(const Packing& model, const std::string& sides) {
  const std::size_t n = model.size();
  if (sides == "periodic" && model.box.periodic[0] && model.box.periodic[1]) return model.box.length.x * model.box.length.y;
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& p = model.position[k];
    const double r = model.radius[k];
    if (model.box.periodic[0]) {
      x0 = model.box.lo.x;
      x1 = model.box.lo.x + model.box.length.x;
    } else {
      x0 = std::min(x0, p.x - r);
      x1 = std::max(x1, p.x + r);
    }
    if (model.box.periodic[1]) {
      y0 = model.box.lo.y;
      y1 = model.box.lo.y + model.box.length.y;
    } else {
      y0 = std::min(y0, p.y - r);
      y1 = std::max(y1, p.y + r);
    }
  }
  return (x1 - x0) * (y1 - y0);
}

}  // namespace

void UniaxialCompressionOptions::validate() const {
  require(strain_rate > 0.0 && std::isfinite(strain_rate), "strain_rate", strain_rate, "> 0 1/s");
  require(max_strain > 0.0 && max_strain < 0.5, "max_strain", max_strain, "in (0, 0.5)");
  require(stop_drop >= 0.0 && stop_drop < 1.0, "stop_drop", stop_drop, "in [0, 1) (0 = run to max_strain)");
  if (sides != "periodic" && sides != "open") fail_input(fmt::format("sides = {}: must be 'periodic' or 'open'", sides));
  if (plate != "glued" && plate != "contact") fail_input(fmt::format("plate = {}: must be 'glued' or 'contact'", plate));
  require(plate_layers > 0.0 && plate_layers <= 100.0, "plate_layers", plate_layers, "in (0, 100]");
  require(substrate_layers >= 0.0 && substrate_layers <= 100.0, "substrate_layers", substrate_layers, "in [0, 100]");
  require(time_step >= 0.0 && std::isfinite(time_step), "time_step", time_step, ">= 0 s (0 = automatic)");
  require(time_step_safety > 0.0 && time_step_safety <= 1.0, "time_step_safety", time_step_safety, "in (0, 1]");
  require(samples >= 10 && samples <= 10000000, "samples", static_cast<double>(samples), "in [10, 1e7]");
  require(modulus_lower >= 0.0 && modulus_lower < 1.0, "modulus_lower", modulus_lower, "in [0, 1)");
  require(modulus_window > 0.0 && modulus_window <= 1.0, "modulus_window", modulus_window, "in (0, 1]");
  require(threads >= 0, "threads", threads, ">= 0 (0 = all cores)");
  for (double s : snapshot_strains)
    require(s > 0.0 && s <= max_strain, "snapshot strain", s, "in (0, max_strain]");
  if (types.empty()) fail_input("compression test: no particle type parameters given");
  if (bond_materials.empty()) fail_input("compression test: no bond material parameters given");
}

UniaxialCompressionSpecimen prepare_uniaxial_compression(const Packing& bonded_model,
                                                         const UniaxialCompressionOptions& options,
                                                         UniaxialCompressionResult& result) {
  options.validate();
  bonded_model.validate();
  if (bonded_model.size() == 0) fail_input("compression test: the model has no particles");
  if (bonded_model.bonds.empty())
    fail_input("compression test: the model has no bonds (make them with `packlab bond IN --model elastic`)");

  Packing model = bonded_model;
  model.velocity.clear();
  model.angular_velocity.clear();
  // Open z, and x, y for open sides; drop the bonds across an opened boundary.
  std::array<bool, 3> open_axis{options.sides == "open", options.sides == "open", true};
  for (int a = 0; a < 3; ++a)
    if (open_axis[static_cast<std::size_t>(a)]) model.box.periodic[static_cast<std::size_t>(a)] = false;
  const std::size_t n = model.size();
  // Substrate.
  bool any_fixed = false;
  for (auto f : model.fixed) any_fixed = any_fixed || f;
  double zmin = std::numeric_limits<double>::infinity(), bottom = zmin, top = -zmin, dsum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    zmin = std::min(zmin, model.position[k].z);
    bottom = std::min(bottom, model.position[k].z - model.radius[k]);
    top = std::max(top, model.position[k].z + model.radius[k]);
    dsum += 2.0 * model.radius[k];
  }
  if (!any_fixed) {
    if (!(options.substrate_layers > 0.0))
      fail_input("substrate_layers = 0: the model has no fixed particles, so at least one substrate layer must be fixed");
    const double cut = zmin + (options.substrate_layers - 0.5) * dsum / static_cast<double>(n);
    model.fixed.assign(n, 0);
    for (std::size_t k = 0; k < n; ++k) model.fixed[k] = model.position[k].z < cut ? 1 : 0;
  }
  if (model.fixed.empty()) model.fixed.assign(n, 0);
  for (auto f : model.fixed) result.fixed_particles += f ? 1 : 0;
  // Glued plate: the top layers become fixed particles driven with the plate.
  const bool glued = options.plate == "glued";
  std::vector<std::uint8_t> grip(n, 0);
  double substrate_top = -std::numeric_limits<double>::infinity(), grip_bottom = -substrate_top, zmax = substrate_top;
  for (std::size_t k = 0; k < n; ++k) {
    zmax = std::max(zmax, model.position[k].z);
    if (model.fixed[k]) substrate_top = std::max(substrate_top, model.position[k].z);
  }
  if (glued) {
    const double cut = zmax - (options.plate_layers - 0.5) * dsum / static_cast<double>(n);
    for (std::size_t k = 0; k < n; ++k)
      if (!model.fixed[k] && model.position[k].z > cut) {
        grip[k] = 1;
        model.fixed[k] = 1;
        grip_bottom = std::min(grip_bottom, model.position[k].z);
        ++result.glued_particles;
      }
    if (result.glued_particles == 0 || !(grip_bottom > substrate_top))
      fail_input("compression test: the glued plate layers and the substrate meet (sample too thin for "
                 "plate_layers + substrate_layers)");
  }
  if (result.fixed_particles == 0 || result.fixed_particles + result.glued_particles >= n)
    fail_input(fmt::format("compression test: {} of {} particles are fixed; the substrate must hold some but not all",
                           result.fixed_particles, n));
  {
    Bonds kept;
    const Bonds& in = model.bonds;
    for (std::size_t b = 0; b < in.size(); ++b) {
      bool drop = in.state[b] != 0;
      for (std::size_t a = 0; a < 3; ++a) drop = drop || (open_axis[a] && in.image[b][a] != 0);
      drop = drop || (model.fixed[static_cast<std::size_t>(in.i[b])] && model.fixed[static_cast<std::size_t>(in.j[b])]);
      if (drop) {
        ++result.dropped_bonds;
        continue;
      }
      kept.add(in.i[b], in.j[b], in.image[b], in.material[b], in.rest_length[b], 0);
    }
    model.bonds = std::move(kept);
  }
  if (model.bonds.empty()) fail_input("compression test: no load-bearing bonds left (all between fixed particles or across opened boundaries)");
  result.bonds = model.bonds.size();
  result.particles = n;

  // Cross-section and height.
  result.area = cross_section_area(model, options.sides);
  result.height = glued ? grip_bottom - substrate_top : top - bottom;
  return {std::move(model), std::move(grip), top};
}

}  // namespace packlab::mechanics
