// Uniaxial compression: the options and the specimen (opened axes, substrate, glued plate,
// load-bearing bonds, cross-section and gauge height). The loading: uniaxial_compression.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "packlab/core/error.hpp"
#include "packlab/io/options.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"

namespace packlab::mechanics {

namespace {

// The width of the specimen along x or y: the box's along a periodic side, the spheres' along an
// open one.
double width(const Packing& model, int axis) {
  const bool periodic = model.box.periodic[static_cast<std::size_t>(axis)];
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t k = 0; k < model.size(); ++k) {
    const double x = model.position[k][axis];
    const double r = model.radius[k];
    if (periodic) {
      lo = model.box.lo[axis];
      hi = model.box.lo[axis] + model.box.length[axis];
    } else {
      lo = std::min(lo, x - r);
      hi = std::max(hi, x + r);
    }
  }
  return hi - lo;
}

// A: the periodic cross-section Lx Ly, or the x-y extent of the spheres along open sides.
double cross_section_area(const Packing& model, const std::string& sides) {
  if (sides == "periodic" && model.box.periodic[0] && model.box.periodic[1])
    return model.box.length.x * model.box.length.y;
  return width(model, 0) * width(model, 1);
}

}  // namespace

void UniaxialCompressionOptions::validate() const {
  UniaxialCompressionOptions copy = *this;
  copy.on_point = nullptr;
  io::ConfigSchema ranges("test compress");
  io::add_uniaxial_compression_options(ranges, copy);
  ranges.validate();
  // Set by UniaxialCompressionSetup::finish (or the caller), not an option of the front ends.
  require(strain_rate > 0.0 && std::isfinite(strain_rate), "strain_rate", strain_rate, "> 0 1/s");
  if (sides != "periodic" && sides != "open")
    fail_input(fmt::format("sides = {}: must be 'periodic' or 'open'", sides));
  if (plate != "glued" && plate != "contact")
    fail_input(fmt::format("plate = {}: must be 'glued' or 'contact'", plate));
  if (solver != "dynamic" && solver != "static")
    fail_input(fmt::format("solver = {}: must be 'dynamic' or 'static'", solver));
  if (solver == "static" && elastic_speedup > 1.0)
    fail_input(
        fmt::format("elastic_speedup = {:g} with solver = static: the adaptive rate is the dynamic solver's (the "
                    "static one has no rate)",
                    elastic_speedup));
  if (solver == "static" && plate != "glued")
    fail_input(
        "plate = contact with solver = static: the static solver needs the glued plate (a contact plate "
        "touches a rough top at a few points and takes no load until it has pressed in, which a linear "
        "solve about the start cannot follow)");
  for (double s : snapshot_strains)
    require(s > 0.0 && s <= max_strain, "snapshot_strains", s, fmt::format("in (0, max_strain = {:g}]", max_strain));
  for (double s : snapshot_stresses) require(s > 0.0 && std::isfinite(s), "snapshot_stresses", s, "> 0 Pa");
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
      fail_input(
          "substrate_layers = 0: the model has no fixed particles, so at least one substrate layer must be fixed");
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
      fail_input(
          "compression test: the glued plate layers and the substrate meet (sample too thin for "
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
  if (model.bonds.empty())
    fail_input(
        "compression test: no load-bearing bonds left (all between fixed particles or across opened boundaries)");
  result.bonds = model.bonds.size();
  result.particles = n;

  // Cross-section and height.
  result.area = cross_section_area(model, options.sides);
  result.height = glued ? grip_bottom - substrate_top : top - bottom;
  return {std::move(model), std::move(grip), top};
}

}  // namespace packlab::mechanics
