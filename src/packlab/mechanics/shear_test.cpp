#include "packlab/mechanics/shear_test.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "packlab/core/error.hpp"
#include "packlab/dem/material.hpp"
#include "packlab/mechanics/calibration.hpp"

namespace packlab::mechanics {

namespace {

constexpr const char* axis_names = "xyz";

int axis_from_name(const std::string& s, const std::string& spec) {
  if (s == "x") return 0;
  if (s == "y") return 1;
  if (s == "z") return 2;
  fail_input(fmt::format("--orientations = {}: '{}' is not an axis; allowed: all, or plate normals x,y,z, or "
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

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
      if (n == d) fail_input(fmt::format("--orientations = {}: '{}' shears along the plate normal", spec, item));
      out.push_back({n, d});
    }
  }
  if (out.empty()) fail_input(fmt::format("--orientations = '{}': empty; allowed: all, x,y,z or pairs like z:x", spec));
  return out;
}

std::string orientation_name(const ShearOrientation& o) {
  return fmt::format("{}:{}", axis_names[o.normal], axis_names[o.direction]);
}

void validate(const ShearTestOptions& o) {
  require(o.normal_stiffness > 0.0 && std::isfinite(o.normal_stiffness), "normal_stiffness", o.normal_stiffness,
          "> 0 N/m");
  require(o.shear_stiffness >= 0.0 && std::isfinite(o.shear_stiffness), "shear_stiffness", o.shear_stiffness,
          ">= 0 N/m");
  require(o.normal_strength > 0.0, "normal_strength", o.normal_strength, "> 0 N (inf: never breaks)");
  require(o.shear_strength > 0.0, "shear_strength", o.shear_strength, "> 0 N (inf: never breaks)");
  require(o.friction >= 0.0 && std::isfinite(o.friction), "friction", o.friction, ">= 0");
  require(o.damping >= 0.0 && o.damping < 1.0, "damping", o.damping, "in [0, 1)");
  require(o.density > 0.0 && std::isfinite(o.density), "density", o.density, "> 0 kg/m^3");
  (void)dem::stiffness_rule_from_name(o.stiffness_rule);
  require(o.cycles >= 1 && o.cycles <= 1000, "cycles", o.cycles, "in [1, 1000]");
  require(o.amplitude > 0.0 && o.amplitude <= 0.1, "amplitude", o.amplitude, "in (0, 0.1] (deflection / box edge)");
  require(o.samples_per_cycle >= 8 && o.samples_per_cycle % 4 == 0, "samples_per_cycle", o.samples_per_cycle,
          "a multiple of 4, >= 8");
  require(o.steps_per_cycle >= o.samples_per_cycle && o.steps_per_cycle % o.samples_per_cycle == 0,
          "steps_per_cycle", static_cast<double>(o.steps_per_cycle),
          fmt::format("a multiple of samples_per_cycle ({})", o.samples_per_cycle));
  require(o.plate_layers >= 1 && o.plate_layers <= 10, "plate_layers", o.plate_layers, "in [1, 10]");
  require(o.regions >= 1 && o.regions <= 50, "regions", o.regions, "in [1, 50]");
  require(o.time_step_safety > 0.0 && o.time_step_safety <= 1.0, "time_step_safety", o.time_step_safety, "in (0, 1]");
  require(o.threads >= 0, "threads", o.threads, ">= 0 (0 = all cores)");
  if (o.orientations.empty()) fail_input("orientations: at least one is needed");
  for (const auto& r : o.orientations)
    if (r.normal < 0 || r.normal > 2 || r.direction < 0 || r.direction > 2 || r.normal == r.direction)
      fail_input(fmt::format("orientation ({}, {}): axes must be 0, 1, 2 and differ", r.normal, r.direction));
}

dem::EngineConfig shear_engine_config(const ShearTestOptions& o) {
  dem::EngineConfig c;
  c.contact_law = "linear";
  dem::Material t;
  t.normal_stiffness = o.normal_stiffness;
  t.shear_stiffness = o.shear_stiffness;
  t.friction = o.friction;
  t.density = o.density;
  t.damping = o.damping;
  c.types = {t};
  c.stiffness_rule = dem::stiffness_rule_from_name(o.stiffness_rule);
  // The bond acts with the contact stiffness of the pair (PFC: the linear contact law extended
  // into tension), i.e. the particle stiffnesses in series under the particle rule.
  const double factor = c.stiffness_rule == dem::StiffnessRule::particle ? 0.5 : 1.0;
  c.bond_materials = dem::BondMaterialList<dem::ContactBond>{
      dem::ContactBond::Params{factor * o.normal_stiffness, factor * o.shear_stiffness, o.normal_strength,
                               o.shear_strength}};
  c.time_step_safety = o.time_step_safety;
  c.threads = o.threads;
  return c;
}

namespace {

void require_periodic_bonded(const Packing& p) {
  p.validate();
  if (!(p.box.periodic[0] && p.box.periodic[1] && p.box.periodic[2]))
    fail_input("test shear: the packing's box must be periodic along x, y and z (the plates are its periodic "
               "images)");
  bool intact = false;
  for (int s : p.bonds.state) intact = intact || s == 0;
  if (!intact) fail_input("test shear: the packing has no intact bond; make a bonded model first (packlab bond IN "
                          "--model contact --out FILE.vtu)");
}

}  // namespace

Packing relax_bonded(const Packing& bonded, const ShearTestOptions& options, dem::ZeroVelocityRelaxResult* result) {
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
  for (int a = 0; a < 3; ++a) out.box.periodic[static_cast<std::size_t>(a)] = p.box.periodic[static_cast<std::size_t>(axis[a])];
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
    fail_input(fmt::format("test shear: {} plate layers ({:.4g} m) are thicker than the box edge along the plate "
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

ShearCycle evaluate_cycle(const std::vector<ShearSample>& samples, int cycle) {
  ShearCycle c;
  c.cycle = cycle;
  // Least squares sigma = a sin(phi) + b cos(phi) + c0 (normal equations of three unknowns).
  double smin = std::numeric_limits<double>::infinity(), smax = -smin, gmin = smin, gmax = -smin;
  double pmin = smin, pmax = -smin;
  double Sss = 0, Scc = 0, Ssc = 0, Ss = 0, Sc = 0, S1 = 0, Sys = 0, Syc = 0, Sy = 0;
  double Gs = 0, Gc = 0, G1 = 0;
  for (const auto& x : samples) {
    if (x.cycle != cycle) continue;
    smin = std::min(smin, x.stress);
    smax = std::max(smax, x.stress);
    pmin = std::min(pmin, x.plate_stress);
    pmax = std::max(pmax, x.plate_stress);
    gmin = std::min(gmin, x.strain);
    gmax = std::max(gmax, x.strain);
    const double s = std::sin(x.phase), co = std::cos(x.phase);
    Sss += s * s;
    Scc += co * co;
    Ssc += s * co;
    Ss += s;
    Sc += co;
    S1 += 1.0;
    Sys += x.stress * s;
    Syc += x.stress * co;
    Sy += x.stress;
    Gs += x.strain * s;
    Gc += x.strain * co;
    G1 += x.strain;
  }
  if (S1 < 3.0 || !(gmax > gmin)) return c;
  // Solve the 3x3 system by Cramer's rule.
  const double M[3][3] = {{Sss, Ssc, Ss}, {Ssc, Scc, Sc}, {Ss, Sc, S1}};
  auto det3 = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  auto solve = [&](double r0, double r1, double r2, double out[3]) {
    const double d = det3(M);
    for (int col = 0; col < 3; ++col) {
      double A[3][3];
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) A[r][k] = M[r][k];
      A[0][col] = r0;
      A[1][col] = r1;
      A[2][col] = r2;
      out[col] = det3(A) / d;
    }
  };
  double stress_fit[3], strain_fit[3];
  solve(Sys, Syc, Sy, stress_fit);
  solve(Gs, Gc, G1, strain_fit);
  // Phase of the stress relative to the strain's own phase (the strain is a sine by
  // construction; fitting it too removes any sampling offset).
  const double stress_phase = std::atan2(stress_fit[1], stress_fit[0]);
  const double strain_phase = std::atan2(strain_fit[1], strain_fit[0]);
  double delta = stress_phase - strain_phase;
  while (delta > std::numbers::pi) delta -= 2.0 * std::numbers::pi;
  while (delta < -std::numbers::pi) delta += 2.0 * std::numbers::pi;
  c.strain_amplitude = 0.5 * (gmax - gmin);
  c.stress_amplitude = 0.5 * (smax - smin);
  c.complex_modulus = c.stress_amplitude / c.strain_amplitude;
  c.phase_angle = delta;
  c.storage_modulus = c.complex_modulus * std::cos(delta);
  c.loss_modulus = c.complex_modulus * std::sin(delta);
  c.plate_storage_modulus = 0.5 * (pmax - pmin) / c.strain_amplitude * std::cos(delta);
  return c;
}

ShearRun run_shear_orientation(const Packing& bonded, const ShearOrientation& orientation,
                               const ShearTestOptions& options) {
  validate(options);
  require_periodic_bonded(bonded);
  const auto t0 = std::chrono::steady_clock::now();
  ShearRun run;
  run.orientation = orientation;
  const std::string stage = orientation_name(orientation);
  ShearSetup setup = build_shear_setup(oriented_packing(bonded, orientation), options.plate_layers, options.regions);
  run.structure_particles = setup.structure;
  run.plate_particles = setup.lower + setup.upper;
  run.bonds = setup.packing.bonds.size();
  dem::Engine engine(setup.packing, shear_engine_config(options));
  run.time_step = engine.time_step();
  const std::size_t bonds_before = engine.intact_bonds();

  // Settle the set-up (plates fixed): the bond shear histories of the §2.2 relaxation are not
  // carried over, so balance the forces again with the same procedure.
  if (options.settle) {
    dem::ZeroVelocityRelaxOptions ro = options.relax_options;
    run.settle = dem::relax_zeroing_velocities(engine, ro);
    run.steps += run.settle.steps;
  }

  // Internal indices of the upper plate.
  std::vector<std::size_t> upper;
  for (std::size_t k = 0; k < engine.particle_count(); ++k)
    if (setup.role[static_cast<std::size_t>(engine.original_index()[k])] == 2) upper.push_back(k);

  const double H = setup.height;
  const double dt = engine.time_step();
  const long S = options.steps_per_cycle;
  const long interval = S / options.samples_per_cycle;
  const double region_volume = setup.area * setup.region_thickness;
  const long total = S * options.cycles;
  double deflection = 0.0;
  double max_kinetic = 0.0, max_strain_energy = 0.0;
  auto& P = engine.particles();

  auto sample = [&](int cycle, long step, double phase, const dem::Diagnostics& d) {
    ShearSample x;
    x.cycle = cycle;
    x.step = step;
    x.time = static_cast<double>(step) * dt;
    x.phase = phase;
    x.strain = deflection / H;
    x.kinetic_energy = d.kinetic_energy;
    x.strain_energy = d.strain_energy;
    x.region_stress.assign(static_cast<std::size_t>(options.regions), 0.0);
    const dem::ContactForces f = engine.contact_forces();
    double plate_force = 0.0;
    for (std::size_t c = 0; c < f.size(); ++c) {
      if (f.j[c] < 0) continue;
      const auto i = static_cast<std::size_t>(f.i[c]), j = static_cast<std::size_t>(f.j[c]);
      const Vec3& l = f.branch[c];
      const Vec3& F = f.force[c];
      // Symmetric x'z' part of 1/2 l (x) F for each end (i: l, -F; j: -l, F: the same product).
      const double lf = 0.5 * 0.5 * (l.x * F.z + l.z * F.x);
      if (setup.region[i] >= 0) x.region_stress[static_cast<std::size_t>(setup.region[i])] += lf;
      if (setup.region[j] >= 0) x.region_stress[static_cast<std::size_t>(setup.region[j])] += lf;
      const bool iu = setup.role[i] == 2, ju = setup.role[j] == 2;
      if (ju && !iu) plate_force += F.x;
      if (iu && !ju) plate_force -= F.x;
      if (f.kind[c] == dem::ContactForces::bond) {
        const double len = norm(l);
        if (len > 0.0) {
          const Vec3 nrm = l * (1.0 / len);
          const double fn = dot(F, nrm);  // > 0: pushes j away (compression)
          const double fs = norm(F - fn * nrm);
          run.max_bond_tension = std::max(run.max_bond_tension, -fn);
          run.max_bond_shear_force = std::max(run.max_bond_shear_force, fs);
        }
      }
    }
    // particle_stress sums l_a F_b with l from the particle to its partner and F the force on
    // the particle: for i that is l (x) (-F); tension positive. The sum above used l (x) F.
    double mean = 0.0;
    for (double& s : x.region_stress) {
      s = -s / region_volume;
      mean += s;
    }
    x.stress = mean / static_cast<double>(options.regions);
    x.plate_stress = -plate_force / setup.area;
    max_kinetic = std::max(max_kinetic, d.kinetic_energy);
    max_strain_energy = std::max(max_strain_energy, d.strain_energy);
    run.samples.push_back(std::move(x));
  };

  long done = 0;
  for (int cycle = 1; cycle <= options.cycles; ++cycle) {
    const double A = options.amplitude * H * cycle / options.cycles;
    for (long s = 0; s < S; ++s) {
      const double u0 = A * std::sin(2.0 * std::numbers::pi * static_cast<double>(s) / static_cast<double>(S));
      const double u1 = A * std::sin(2.0 * std::numbers::pi * static_cast<double>(s + 1) / static_cast<double>(S));
      const double v = (u1 - u0) / dt;
      for (std::size_t k : upper) P.velocity[k] = Vec3{v, 0.0, 0.0};
      const bool measure = (s + 1) % interval == 0;
      if (measure) {
        const dem::Diagnostics d = engine.step_measured();
        deflection += v * dt;
        ++done;
        sample(cycle, done, 2.0 * std::numbers::pi * static_cast<double>(s + 1) / static_cast<double>(S), d);
        if (options.progress) options.progress(stage, done, total);
      } else {
        engine.run(1);
        deflection += v * dt;
        ++done;
      }
    }
  }
  for (std::size_t k : upper) P.velocity[k] = Vec3{};
  run.steps += done;
  run.broken_bonds = bonds_before - engine.intact_bonds();
  for (int cycle = 1; cycle <= options.cycles; ++cycle) run.cycles.push_back(evaluate_cycle(run.samples, cycle));
  for (const auto& c : run.cycles) {
    run.storage_modulus += c.storage_modulus;
    run.complex_modulus += c.complex_modulus;
    run.phase_angle += c.phase_angle;
    run.plate_storage_modulus += c.plate_storage_modulus;
  }
  const double nc = static_cast<double>(run.cycles.size());
  run.storage_modulus /= nc;
  run.complex_modulus /= nc;
  run.phase_angle /= nc;
  run.plate_storage_modulus /= nc;
  run.max_kinetic_to_strain = max_strain_energy > 0.0 ? max_kinetic / max_strain_energy : 0.0;
  run.max_bond_tension_ratio = run.max_bond_tension / options.normal_strength;
  run.max_bond_shear_ratio = run.max_bond_shear_force / options.shear_strength;
  run.seconds = seconds_since(t0);
  return run;
}

ShearTestResult run_shear_test(const Packing& bonded, const ShearTestOptions& options) {
  validate(options);
  require_periodic_bonded(bonded);
  const auto t0 = std::chrono::steady_clock::now();
  ShearTestResult result;
  if (options.relax) {
    result.relaxed_packing = relax_bonded(bonded, options, &result.relax);
    result.relaxed = true;
    result.particle_steps += static_cast<double>(bonded.size()) * static_cast<double>(result.relax.steps);
  } else {
    result.relaxed_packing = bonded;
  }
  for (const auto& o : options.orientations) {
    result.runs.push_back(run_shear_orientation(result.relaxed_packing, o, options));
    const ShearRun& r = result.runs.back();
    result.particle_steps += static_cast<double>(r.structure_particles + r.plate_particles) * static_cast<double>(r.steps);
  }
  double sum = 0.0;
  for (const auto& r : result.runs) {
    sum += r.storage_modulus;
    result.phase_angle_mean += r.phase_angle;
    for (const auto& c : r.cycles) result.phase_angle_max = std::max(result.phase_angle_max, std::abs(c.phase_angle));
  }
  const double n = static_cast<double>(result.runs.size());
  result.storage_modulus_mean = sum / n;
  result.phase_angle_mean /= n;
  double var = 0.0;
  for (const auto& r : result.runs) var += (r.storage_modulus - result.storage_modulus_mean) * (r.storage_modulus - result.storage_modulus_mean);
  result.storage_modulus_std = result.runs.size() > 1 ? std::sqrt(var / (n - 1.0)) : 0.0;
  result.seconds = seconds_since(t0);
  return result;
}

ShearCalibrationResult calibrate_normal_stiffness(const Packing& bonded, double target, const ShearTestOptions& options,
                                                  double tolerance, int max_iterations) {
  validate(options);
  require(target > 0.0 && std::isfinite(target), "target storage modulus", target, "> 0 Pa");
  ShearTestOptions o = options;
  // The §2.2 relaxation does not depend on k_n (a step moves x by F/m dt^2 and dt^2 ~ m/k), so
  // relax once and shear the same structure at every k_n.
  const Packing relaxed = o.relax ? relax_bonded(bonded, o) : bonded;
  const double ratio = options.shear_stiffness / options.normal_stiffness;
  ShearCalibrationResult out;
  auto response = [&](const std::vector<double>& p) {
    ShearTestOptions e = o;
    e.normal_stiffness = p[0];
    e.shear_stiffness = ratio * p[0];
    e.relax = false;
    ShearTestResult r = run_shear_test(relaxed, e);
    out.tried_normal_stiffness.push_back(p[0]);
    out.tried_storage_modulus.push_back(r.storage_modulus_mean);
    return std::vector<double>{r.storage_modulus_mean};
  };
  CalibrationOptions co;
  co.tolerance = tolerance;
  co.max_iterations = max_iterations;
  const CalibrationResult c = calibrate(response, {options.normal_stiffness}, {target}, co);
  out.normal_stiffness = c.parameters[0];
  out.shear_stiffness = ratio * c.parameters[0];
  out.storage_modulus = c.responses[0];
  out.converged = c.converged;
  out.iterations = c.iterations;
  out.evaluations = c.evaluations;
  out.reason = c.reason();
  return out;
}

}  // namespace packlab::mechanics
