// Oscillatory shear: orientations, options, the engine configuration, the relaxation of the
// periodic structure and the test set-up (plates from the periodic repetition, regions).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "packlab/core/error.hpp"
#include "packlab/dem/material.hpp"
#include "packlab/io/options.hpp"
#include "packlab/mechanics/oscillatory_shear.hpp"

namespace packlab::mechanics {

namespace {

constexpr const char* axis_names = "xyz";

int axis_from_name(const std::string& s, const std::string& spec) {
  if (s == "x") return 0;
  if (s == "y") return 1;
  if (s == "z") return 2;
  fail_input(
      fmt::format("orientations = {}: '{}' is not an axis; allowed: all, or plate normals x,y,z, or "
                  "normal:direction pairs such as z:x",
                  spec, s));
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(s);
  while (std::getline(in, item, sep)) {
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    out.push_back(item);
  }
  return out;
}

}  // namespace

std::vector<ShearOrientation> shear_orientations(const std::string& spec) {
  std::vector<ShearOrientation> out;
  if (spec == "all") {
    for (int n = 0; n < 3; ++n)
      for (int d = 0; d < 3; ++d)
        if (d != n) out.push_back({n, d});
    return out;
  }
  for (const std::string& item : split(spec, ',')) {
    const auto colon = item.find(':');
    if (colon == std::string::npos) {
      const int n = axis_from_name(item, spec);
      for (int d = 0; d < 3; ++d)
        if (d != n) out.push_back({n, d});
    } else {
      const int n = axis_from_name(item.substr(0, colon), spec);
      const int d = axis_from_name(item.substr(colon + 1), spec);
      if (n == d) fail_input(fmt::format("orientations = {}: '{}' shears along the plate normal", spec, item));
      out.push_back({n, d});
    }
  }
  if (out.empty()) fail_input(fmt::format("orientations = '{}': empty; allowed: all, x,y,z or pairs like z:x", spec));
  return out;
}

std::string orientation_name(const ShearOrientation& o) {
  return fmt::format("{}:{}", axis_names[o.normal], axis_names[o.direction]);
}

void validate(const OscillatoryShearOptions& o) {
  OscillatoryShearOptions copy = o;
  io::ConfigSchema ranges("test shear");
  io::add_oscillatory_shear_options(ranges, copy);
  ranges.validate();
  (void)dem::stiffness_rule_from_name(o.stiffness_rule);
  // Samples at phases 2 pi k / n with n a multiple of 4 hit the peaks and zeros of the sine.
  require(o.samples_per_cycle % 4 == 0, "samples_per_cycle", o.samples_per_cycle, "a multiple of 4, >= 8");
  require(o.steps_per_cycle >= o.samples_per_cycle && o.steps_per_cycle % o.samples_per_cycle == 0, "steps_per_cycle",
          static_cast<double>(o.steps_per_cycle),
          fmt::format("a multiple of samples_per_cycle ({})", o.samples_per_cycle));
  (void)shear_orientations(o.orientations);
  if (o.solver != "dynamic" && o.solver != "static")
    fail_input(fmt::format("solver = {}: must be 'dynamic' or 'static'", o.solver));
}

dem::EngineConfig shear_engine_config(const OscillatoryShearOptions& o) {
  dem::EngineConfig c;
  c.contact_law = "linear";
  c.types = {dem::Material{.normal_stiffness = o.normal_stiffness,
                           .shear_stiffness = o.shear_stiffness,
                           .friction = o.friction,
                           .density = o.density,
                           .damping = o.damping}};
  c.stiffness_rule = dem::stiffness_rule_from_name(o.stiffness_rule);
  // The bond acts with the contact stiffness of the pair (PFC: the linear contact law extended
  // into tension), i.e. the particle stiffnesses in series under the particle rule.
  const double factor = c.stiffness_rule == dem::StiffnessRule::particle ? 0.5 : 1.0;
  c.bond_materials = dem::BondMaterialList<dem::ContactBond>{dem::ContactBond::Params{
      factor * o.normal_stiffness, factor * o.shear_stiffness, o.normal_strength, o.shear_strength}};
  c.time_step_safety = o.time_step_safety;
  c.threads = o.threads;
  c.adapt_threads = o.adapt_threads;
  return c;
}

Packing relax_bonded(const Packing& bonded, const OscillatoryShearOptions& options,
                     dem::ZeroVelocityRelaxResult* result) {
  dem::Engine engine(bonded, shear_engine_config(options));
  dem::ZeroVelocityRelaxOptions ro = options.relax_options;
  if (options.progress) {
    ro.on_check = [&](const dem::Diagnostics& d, double) { options.progress("relax", d.step, ro.max_steps); };
  }
  dem::ZeroVelocityRelaxResult r = dem::relax_zeroing_velocities(engine, ro);
  Packing out = engine.packing();
  out.velocity.clear();
  out.angular_velocity.clear();
  // The bond states as the engine left them are not exported; count breaks through the
  // diagnostics (none are expected: the relaxation only removes strain).
  if (result) *result = std::move(r);
  return out;
}

Packing oriented_packing(const Packing& p, const ShearOrientation& o) {
  const int third = 3 - o.normal - o.direction;
  const int axis[3] = {o.direction, third, o.normal};  // new axis a takes old axis axis[a]
  auto permute = [&](const Vec3& v) { return Vec3{v[axis[0]], v[axis[1]], v[axis[2]]}; };
  Packing out = p;
  out.box.lo = permute(p.box.lo);
  out.box.length = permute(p.box.length);
  for (int a = 0; a < 3; ++a)
    out.box.periodic[static_cast<std::size_t>(a)] = p.box.periodic[static_cast<std::size_t>(axis[a])];
  for (auto& x : out.position) x = permute(x);
  for (auto& v : out.velocity) v = permute(v);
  for (auto& w : out.angular_velocity) w = permute(w);
  for (auto& im : out.bonds.image) {
    const std::array<int, 3> old = im;
    for (int a = 0; a < 3; ++a) im[static_cast<std::size_t>(a)] = old[static_cast<std::size_t>(axis[a])];
  }
  return out;
}

ShearSetup build_shear_setup(const Packing& in, int plate_layers, int regions) {
  require(plate_layers >= 1, "plate_layers", plate_layers, ">= 1");
  require(regions >= 1, "regions", regions, ">= 1");
  ShearSetup s;
  const std::size_t n = in.size();
  const double H = in.box.length.z;
  const double z0 = in.box.lo.z;
  double r_sum = 0.0, r_max = 0.0;
  for (double r : in.radius) {
    r_sum += r;
    r_max = std::max(r_max, r);
  }
  const double thickness = plate_layers * 2.0 * r_sum / static_cast<double>(std::max<std::size_t>(n, 1));
  if (thickness >= H)
    fail_input(
        fmt::format("test shear: {} plate layers ({:.4g} m) are thicker than the box edge along the plate "
                    "normal ({:.4g} m)",
                    plate_layers, thickness, H));
  s.height = H;
  s.area = in.box.length.x * in.box.length.y;
  s.region_thickness = H / (regions + 1);

  Packing& out = s.packing;
  out.box.lo = {in.box.lo.x, in.box.lo.y, z0 - thickness - 2.0 * r_max};
  out.box.length = {in.box.length.x, in.box.length.y, H + 2.0 * thickness + 4.0 * r_max};
  out.box.periodic = {true, true, false};
  const bool has_density = !in.density.empty();
  std::vector<Vec3> position(n);
  for (std::size_t k = 0; k < n; ++k) position[k] = in.box.wrap(in.position[k]);
  auto push = [&](std::size_t k, double dz, int role) {
    out.add({position[k].x, position[k].y, position[k].z + dz}, in.radius[k], in.type[k]);
    if (has_density) out.density.push_back(in.density[k]);
    out.fixed.push_back(role == 0 ? 0 : 1);
    s.role.push_back(role);
    int region = -1;
    if (role == 0) {
      // Slab k covers heights H (k + 1/2) / (regions + 1) .. H (k + 3/2) / (regions + 1).
      const double h = (position[k].z - z0) / s.region_thickness - 0.5;
      if (h >= 0.0 && h < regions) region = static_cast<int>(std::floor(h));
    }
    s.region.push_back(region);
    return static_cast<int>(out.size()) - 1;
  };
  for (std::size_t k = 0; k < n; ++k) push(k, 0.0, 0);
  // Plates: the periodic images of the structure within `thickness` below and above the box.
  std::vector<int> lower(n, -1), upper(n, -1);
  for (std::size_t k = 0; k < n; ++k)
    if (position[k].z >= z0 + H - thickness) lower[k] = push(k, -H, 1);
  for (std::size_t k = 0; k < n; ++k)
    if (position[k].z < z0 + thickness) upper[k] = push(k, H, 2);
  s.structure = n;
  s.lower = static_cast<std::size_t>(std::count(s.role.begin(), s.role.end(), 1));
  s.upper = static_cast<std::size_t>(std::count(s.role.begin(), s.role.end(), 2));

  // Bonds: within the structure as they were (images along x', y'); a bond that crossed the z'
  // boundary bonds the structure particle to the plate copy of its partner, from both ends.
  // The images refer to the wrapped positions: adjust by the wraps of i and j.
  const Bonds& b = in.bonds;
  for (std::size_t q = 0; q < b.size(); ++q) {
    if (b.state[q] != 0) continue;
    const auto i = static_cast<std::size_t>(b.i[q]), j = static_cast<std::size_t>(b.j[q]);
    std::array<int, 3> wi{0, 0, 0}, wj{0, 0, 0};
    (void)in.box.wrap(in.position[i], &wi);
    (void)in.box.wrap(in.position[j], &wj);
    // r_j + image L - r_i with r = wrapped + w L:  image' = image + wj - wi.
    std::array<int, 3> im{};
    for (std::size_t a = 0; a < 3; ++a) im[a] = b.image[q][a] + wj[a] - wi[a];
    const std::array<int, 3> flat{im[0], im[1], 0};
    if (im[2] == 0) {
      out.bonds.add(static_cast<int>(i), static_cast<int>(j), flat, b.material[q], b.rest_length[q]);
      continue;
    }
    if (std::abs(im[2]) > 1) continue;  // a bond longer than the box: cannot occur for bonds < box edge
    const std::vector<int>& plate_of_j = im[2] > 0 ? upper : lower;  // j's copy at +image H
    const std::vector<int>& plate_of_i = im[2] > 0 ? lower : upper;  // i's copy at -image H
    if (plate_of_j[j] >= 0) out.bonds.add(static_cast<int>(i), plate_of_j[j], flat, b.material[q], b.rest_length[q]);
    if (plate_of_i[i] >= 0) out.bonds.add(plate_of_i[i], static_cast<int>(j), flat, b.material[q], b.rest_length[q]);
  }
  return s;
}

}  // namespace packlab::mechanics
