#include "packlab/io/options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "packlab/core/error.hpp"
#include "packlab/io/adapt_threads_help.hpp"

namespace packlab::io {

void add_linear_material(ConfigSchema& schema, const std::string& section, dem::Material& m) {
  std::vector<Parameter<dem::Material>> properties;
  for (const char* name : {"normal_stiffness", "shear_stiffness", "density", "damping", "friction"})
    properties.push_back(dem::material_parameter(name));
  schema.parameters(section, m, properties);
}

namespace {

// Three values per axis (InputError naming `key` otherwise).
void require_per_axis(const char* key, const std::vector<double>& v) {
  if (v.size() != 3) fail_input(fmt::format("{}: must be three values (x, y, z), got {}", key, v.size()));
}

}  // namespace

generate::LatticeParams LatticeOptions::params() const {
  generate::LatticeParams p = lattice;
  p.type = generate::lattice_type_from_name(type);
  require_per_axis("cells", cells);
  for (int a = 0; a < 3; ++a) {
    const double c = cells[static_cast<std::size_t>(a)];
    require(c >= 1.0 && c <= 1e6 && c == std::floor(c), "cells", c, "an integer in [1, 1e6]");
    p.cells[static_cast<std::size_t>(a)] = static_cast<int>(c);
  }
  return p;
}

ConfigSchema lattice_options(LatticeOptions& o) {
  ConfigSchema schema("generate lattice", "A cubic lattice in a matching periodic box.", "generate_lattice");
  schema.text("type", o.type, "Lattice: sc, bcc or fcc")
      .numbers("cells", o.cells, "Unit cells along x, y, z")
      .number("radius", o.lattice.radius, "Sphere radius")
      .unit("m")
      .range(ranges::positive)
      .number("gap", o.lattice.gap, "Surface gap between nearest neighbours; 0 = touching")
      .unit("m")
      .range(ranges::non_negative);
  return schema;
}

generate::RandomPackingParams RandomOptions::params() const {
  generate::RandomPackingParams p = random;
  p.allow_overlap = !no_overlap;
  require_per_axis("periodic", periodic);
  require_per_axis("aspect", aspect);
  for (std::size_t a = 0; a < 3; ++a) {
    require(periodic[a] == 0.0 || periodic[a] == 1.0, "periodic", periodic[a], "1 (periodic) or 0 (open)");
    p.periodic[a] = periodic[a] != 0.0;
    p.aspect[a] = aspect[a];
  }
  return p;
}

ConfigSchema random_options(RandomOptions& o) {
  ConfigSchema schema("generate random", "Uniform random spheres, or random sequential addition without overlaps.",
                      "generate_random");
  schema.integer("particles", o.random.particles, "Number of spheres")
      .range({1.0, ranges::inf, false, true})
      .number("radius", o.random.radius, "Sphere radius")
      .unit("m")
      .range(ranges::positive)
      .number("phi", o.random.volume_fraction, "Nominal volume fraction (sum of sphere volumes / box)")
      .range({0.0, 1.0, true, true})
      .boolean("no_overlap", o.no_overlap, "Random sequential addition: no two spheres overlap (phi < 0.36)")
      .numbers("periodic", o.periodic, "Periodicity along x, y, z (1 periodic, 0 open; e.g. 1,1,0)")
      .numbers("aspect", o.aspect, "Box edge ratios x, y, z")
      .integer("seed", o.seed, "Seed of the random generator");
  return schema;
}

dem::EngineConfig EngineSettings::config() const {
  dem::EngineConfig c = engine;
  c.stiffness_rule = dem::stiffness_rule_from_name(stiffness_rule);
  c.time_step_rule = dem::time_step_rule_from_name(time_step_rule);
  return c;
}

void add_engine_options(ConfigSchema& schema, EngineSettings& s) {
  std::string laws;
  for (const std::string& name : dem::contact_law_names()) laws += (laws.empty() ? "" : ", ") + name;
  schema.text("contact_law", s.engine.contact_law, "Contact law: one of " + laws);
  schema.parameters("", s.engine.types.front(), dem::material_parameters());
  schema
      .text("stiffness_rule", s.stiffness_rule,
            "particle: stiffnesses are PFC particle stiffnesses in series (contact = k/2); contact: they are "
            "contact stiffnesses (LAMMPS kn)")
      .number("time_step", s.engine.time_step, "Time step; 0 = time_step_safety * min sqrt(m/k)")
      .unit("s")
      .range(ranges::non_negative)
      .number("time_step_safety", s.engine.time_step_safety, "Safety factor of the automatic time step")
      .range(ranges::positive)
      .text("time_step_rule", s.time_step_rule,
            "global (from the stiffest contact and lightest particle), contacts or stiffness_sum (refreshed from "
            "the touching pairs, capped at max_time_step)")
      .number("max_time_step", s.engine.max_time_step,
              "Cap of the refreshed time step; 0 = safety * max over particles of sqrt(m_i / k_i)")
      .unit("s")
      .range(ranges::non_negative)
      .number("skin_ratio", s.engine.skin_ratio, "Verlet skin as a fraction of the largest radius")
      .range(ranges::positive)
      .integer("threads", s.engine.threads,
               "OpenMP threads (0 = all cores): the engine starts at one and uses these while probes find them "
               "faster (adapt_threads; docs/engine.md); the results do not depend on the count")
      .range({0.0, 1024.0, false, false})
      .boolean("adapt_threads", s.engine.adapt_threads, adapt_threads_help("With more than one thread"));
}

ConfigSchema engine_options(EngineSettings& s) {
  ConfigSchema schema("Engine", "The DEM engine with one material for every particle type.", "Engine");
  add_engine_options(schema, s);
  return schema;
}

ConfigSchema relax_options(RelaxRun& r) {
  ConfigSchema schema("relax", "Relaxation of a packing until the forces balance (docs/engine.md).", "relax");
  add_engine_options(schema, r);
  schema.integer("steps", r.relax.max_steps, "Step limit")
      .range(ranges::non_negative)
      .number("tolerance", r.relax.tolerance,
              "Stop when the mean unbalanced force ratio falls below this; 0 runs exactly `steps` steps")
      .range(ranges::non_negative)
      .integer("check_interval", r.relax.check_interval, "Steps between diagnostics")
      .range({1.0, ranges::inf, false, true})
      .integer("seed", r.seed, "Accepted for uniformity; relax draws no random numbers")
      .command_only();
  add_checkpoint_seconds(schema, r.checkpoint_seconds);
  return schema;
}

ConfigSchema vem_options(generate::VemParams& p) {
  ConfigSchema schema("generate vem", "The void expansion method (docs/vem.md); flags override the file.",
                      "generate_vem");
  schema.integer("structural", p.structural, "Structural particles N_S")
      .range({2.0, ranges::inf, false, true})
      .integer("voids", p.voids, "Void particles N_V")
      .range({1.0, ranges::inf, false, true})
      .number("phi_s", p.phi_s, "Volume fraction of the structural particles Phi_S")
      .range({0.0, 0.64, true, true})
      .number("radius", p.radius, "Structural radius r_S")
      .unit("m")
      .range(ranges::positive)
      .integer("seed", p.seed, "Seed of the random generator")
      .integer("threads", p.threads, "OpenMP threads (0 = all cores)")
      .range({0.0, 1024.0, false, false})
      .boolean("adapt_threads", p.adapt_threads, adapt_threads_help("With more than one thread"))
      .integer("blowup_steps", p.blowup_steps, "Blow-up steps m of the structural particles")
      .range({1.0, 10000.0, false, false})
      .number("void_radius_ratio", p.void_radius_ratio, "Initial void radius and its growth per cycle, r_V0 / r_S")
      .range({0.0, 1.0, true, false})
      .number("contact_eps", p.contact_eps, "Coordination contact tolerance eps: contact at (1 + eps) 2 r_S")
      .range({0.0, 1.0, false, true})
      .number("void_mass_scaling", p.void_mass_scaling,
              "Void mass scaling c (0 = none; docs/vem.md): quasi-static, results shown not to depend on it")
      .range(ranges::non_negative)
      .text("time_step_rule", p.time_step_rule,
            "'stiffness_sum' (PFC: safety * min sqrt(m_i / sum of i's contact stiffnesses)) or 'contacts' "
            "(safety * min over touching pairs of sqrt(m_lighter / k))")
      .number("time_step_safety", p.time_step_safety, "Time step as a fraction of sqrt(m/k) (PFC's default 0.8)")
      .range({0.0, 1.0, true, false})
      .number("skin", p.skin, "Verlet skin / r_S")
      .range({0.0, 2.0, true, false})
      .number_to_all("damping", {&p.structural_material.damping, &p.void_material.damping},
                     "Local damping of both materials (overridden by the material tables)")
      .number_to_all("friction", {&p.structural_material.friction, &p.void_material.friction},
                     "Friction of both materials (overridden by the material tables)");
  add_linear_material(schema, "structural_material", p.structural_material);
  add_linear_material(schema, "void_material", p.void_material);
  schema.number("relax.tolerance", p.relax_tolerance, "A relaxation ends when the unbalanced force ratio is below this")
      .range(ranges::non_negative)
      .number("relax.overlap", p.relax_overlap, "... or when the largest overlap / (r_i + r_j) is below this")
      .range({0.0, 1.0, false, true})
      .integer("relax.max_steps", p.relax_max_steps, "Step limit of one relaxation")
      .range({1.0, ranges::inf, false, true})
      .integer("relax.check_interval", p.relax_check_interval, "Steps between two checks of the criterion")
      .range({1.0, ranges::inf, false, true})
      .number("stop.strain_energy", p.stop_strain_energy,
              "Stage III: stop when E_strain / (N_S k_n,S r_S^2) exceeds this")
      .range(ranges::positive)
      .number("stop.max_q", p.max_q, "Stop at this q = r_V / r_S at the latest")
      .alias("max_q")
      .number("stop.min_coordination", p.stop_min_coordination,
              "Stage III ends the run only once the structural coordination number CN has reached this too (0 = no "
              "minimum)")
      .range({0.0, 12.0, false, false});
  return schema;
}

void add_shake_params(ConfigSchema& schema, generate::ShakeParams& p) {
  schema
      .text("move_rule", p.move_rule,
            "Shake move: metropolis (a point uniform in the shake window, kept if free, up to max_trials tries) or "
            "freest (along the freest of max_trials directions)")
      .when_not_saved("freest")  // the only rule before move_rule existed
      .number("window", p.window, "Shake window R_sh in units of the particle radius")
      .range({0.0, 1.0, true, false})
      .integer("max_trials", p.max_trials, "Trials per visit N_sh")
      .range({1.0, 1e6, false, false})
      .boolean("adaptive", p.adaptive, "Adapt the shake window to the free distance");
}

generate::SizeClasses LsOptions::classes() const {
  return generate::SizeClasses::from_options(sizes, number_fractions, volume_fractions);
}

void add_ls_params(ConfigSchema& schema, generate::LsParams& p) {
  schema
      .number("growth_rate", p.growth_rate,
              "G = ds/dt: growth of the largest diameter per unit time, in units of its box-filling size and of the "
              "thermal speed")
      .range(ranges::non_negative)
      .number("max_pressure", p.max_reduced_pressure, "Jamming criterion: reduced pressure PV/NkT")
      .range({1.0, ranges::inf, true, true})
      .number("events_per_block", p.events_per_block,
              "Events per particle between velocity rescalings and pressure measurements")
      .range({0.01, 1e6, false, false})
      .number("neighbor_list_limit", p.neighbor_list_limit,
              "Largest mean neighbour-list length the skin may give (an ideal-gas estimate at a block's start, and "
              "the lists a block ended with; bounds the memory of slow growth); 0: no limit")
      .range({0.0, 1000.0, false, false})
      .when_not_saved(0.0);  // runs recorded before the limit existed had none
}

ConfigSchema ls_options(LsOptions& o) {
  ConfigSchema schema("generate ls", "Lubachevsky-Stillinger growth of hard spheres from random points (docs/scrm.md).",
                      "generate_ls");
  schema.number("phi", o.phi, "Target volume fraction; 0: grow until jammed")
      .range({0.0, 1.0, false, true})
      .integer("particles", o.particles, "Number of spheres")
      .numbers("sizes", o.sizes, "Relative diameters of the size classes, e.g. 1,0.313")
      .numbers("number_fractions", o.number_fractions,
               "Number fractions of the classes (normalized; empty: equal numbers)")
      .numbers("volume_fractions", o.volume_fractions, "Volume fractions of the classes (normalized), instead")
      .number("radius", o.radius,
              "Radius of the largest class at the target volume fraction (0.64 when growing to jamming)")
      .unit("m")
      .range(ranges::positive)
      .range(ranges::positive);
  add_ls_params(schema, o.ls);
  schema.integer("seed", o.seed, "Seed of the random generator");
  return schema;
}

generate::ScrmParams ScrmOptions::params() const {
  generate::ScrmParams sp;
  sp.ls = ls;
  sp.ls.target_volume_fraction = phi;
  sp.shake = shake;
  sp.blocks_per_cycle = blocks_per_cycle;
  sp.shakes_per_cycle = shakes_per_cycle;
  sp.final_shakes = final_shakes;
  sp.validate();
  return sp;
}

ConfigSchema scrm_options(ScrmOptions& s) {
  ConfigSchema schema = ls_options(s);
  ConfigSchema scrm("generate scrm",
                    "Shaking collective rearrangement: LS growth alternated with Monte-Carlo shaking (docs/scrm.md).",
                    "generate_scrm");
  scrm.append(schema);
  add_shake_params(scrm, s.shake);
  scrm.integer("blocks_per_cycle", s.blocks_per_cycle, "LS blocks between shakes")
      .range({1.0, ranges::inf, false, true})
      .integer("shakes_per_cycle", s.shakes_per_cycle, "Global shakes after each LS segment")
      .range(ranges::non_negative)
      .integer("final_shakes", s.final_shakes, "Global shakes at the target volume fraction")
      .range(ranges::non_negative);
  return scrm;
}

FbaOptions::Setup FbaOptions::setup() const {
  fba.validate();
  require(diameter > 0.0 && std::isfinite(diameter), "diameter", diameter, "> 0 m");
  if ((particles > 0) == !box.empty()) fail_input("particles and box: give exactly one of them");
  Setup s;
  s.classes = generate::SizeClasses::from_options(sizes, number_fractions, volume_fractions);
  s.box.periodic = generate::periodic_axes_from_name(periodic);
  if (!box.empty()) {
    if (box.size() != 3) fail_input(fmt::format("box: must be three edges LX, LY, LZ, got {}", box.size()));
    for (const double l : box) require(l > 0.0, "box", l, "> 0 m");
    s.box.length = {box[0], box[1], box[2]};
    s.count = generate::fba_count_for_volume(s.box.volume(), fba.target_porosity, diameter, s.classes);
    return s;
  }
  s.count = particles;
  require(particles >= 2 && particles <= 100'000'000, "particles", static_cast<double>(particles), "in [2, 1e8]");
  if (aspect.size() != 3) fail_input(fmt::format("aspect: must be three edge ratios, got {}", aspect.size()));
  for (const double a : aspect) require(a > 0.0, "aspect", a, "> 0");
  const std::vector<double> x = s.classes.number_fractions();
  const double smax = *std::max_element(s.classes.sizes.begin(), s.classes.sizes.end());
  double mean_volume = 0;
  for (std::size_t k = 0; k < x.size(); ++k)
    mean_volume += x[k] * std::numbers::pi / 6.0 * std::pow(s.classes.sizes[k] / smax * diameter, 3);
  const double volume = static_cast<double>(particles) * mean_volume / (1.0 - fba.target_porosity);
  const double edge = std::cbrt(volume / (aspect[0] * aspect[1] * aspect[2]));
  s.box.length = {aspect[0] * edge, aspect[1] * edge, aspect[2] * edge};
  return s;
}

void add_checkpoint_seconds(ConfigSchema& schema, double& seconds) {
  schema.number("output.checkpoint_seconds", seconds, "Wall-clock seconds between checkpoints")
      .unit("s")
      .range(ranges::positive)
      .alias("checkpoint_seconds")
      .command_only();
}

void add_fba_params(ConfigSchema& schema, generate::FbaParams& p) {
  schema.number("porosity", p.target_porosity, "Target porosity 1 - sum V_i / V_box")
      .range({0.30, 1.0, false, true})
      .number("tolerance", p.tolerance, "Stop when the largest overlap (r_i + r_j - d)/(r_i + r_j) is at most this")
      .range({0.0, 0.1, true, false})
      .number("shrink_rate", p.shrink_rate,
              "Fraction of the gap between nominal and true diameter removed per iteration")
      .range({0.0, 1.0, true, false})
      .number("step", p.step, "Fraction of each pair's overlap removed per iteration")
      .range({0.0, 1.0, true, false})
      .number("momentum", p.momentum,
              "Heavy-ball factor of the overlap removal at the target: each move adds this times the previous one")
      .range({0.0, 1.0, false, true})
      .integer("max_iterations", p.max_iterations, "Iteration limit")
      .range({1.0, ranges::inf, false, true})
      .integer("threads", p.threads, "Threads of the neighbour search")
      .range({1.0, 1024.0, false, false});
}

void add_bd_params(ConfigSchema& schema, generate::BdParams& p) {
  schema.integer("particles", p.particles, "Number of spheres N (the box follows, doh-elastic-properties eq. 5)")
      .range({2.0, 1e8, false, false})
      .number("volume_fraction", p.volume_fraction, "Volume fraction Phi of the spheres")
      .range({0.0, 0.6, true, false})
      .alias("phi")
      .number("radius", p.radius, "Sphere radius a")
      .unit("m")
      .range(ranges::positive)
      .number("hamaker_constant", p.hamaker_constant, "Hamaker constant A, particle / liquid / particle")
      .unit("J")
      .range(ranges::non_negative)
      .number("surface_potential", p.surface_potential, "Surface potential psi_0 (constant-potential double layer)")
      .unit("V")
      .range({-1.0, 1.0, false, false})
      .number("debye_length", p.debye_length, "Debye screening length 1/kappa (unless ionic_strength is given)")
      .unit("m")
      .range(ranges::positive)
      .number("ionic_strength", p.ionic_strength,
              "Ionic strength I of a 1:1 electrolyte; > 0 sets the Debye length from it (0: use debye_length)")
      .unit("mol/m^3")
      .range(ranges::non_negative)
      .number("relative_permittivity", p.relative_permittivity, "Relative permittivity eps_r of the liquid")
      .range(ranges::positive)
      .number("temperature", p.temperature, "Temperature T")
      .unit("K")
      .range(ranges::positive)
      .number("viscosity", p.viscosity, "Viscosity eta of the liquid (Stokes drag 6 pi eta a)")
      .unit("Pa s")
      .range(ranges::positive)
      .number("min_separation", p.min_separation, "Surface separation below which the DLVO force is held constant")
      .unit("m")
      .range(ranges::positive)
      .number("cutoff", p.cutoff, "Surface separation beyond which the DLVO potential is cut off")
      .unit("m")
      .range(ranges::positive)
      .number("initial_separation", p.initial_separation, "Smallest surface gap of the random start")
      .unit("m")
      .range(ranges::non_negative)
      .number("bond_separation", p.bond_separation,
              "A pair closer than this surface separation sticks (bonded: the primary minimum)")
      .unit("m")
      .range(ranges::positive)
      .number("bond_stiffness_factor", p.bond_stiffness_factor, "Bond stiffness k_b dt / (6 pi eta a)")
      .range({0.0, 0.08, true, false})
      .boolean("central_bonds", p.central_bonds,
               "Bonds resist stretching only: bonded spheres roll on each other (default: rigid bonds)")
      .number("bond_slip_force", p.bond_slip_force,
              "Tangential force beyond which a rigid bond's contact point slips (rolls on); 0: never")
      .unit("N")
      .range(ranges::non_negative)
      .integer("quench_steps", p.quench_steps, "Noise-free steps at the end that relax the bonds to their rest length")
      .range(ranges::non_negative)
      .number("step_fraction", p.step_fraction, "Rms Brownian displacement per axis and step / Debye length")
      .range({0.0, 1.0, true, false})
      .number("time_step", p.time_step, "Time step (0: from step_fraction)")
      .unit("s")
      .range(ranges::non_negative)
      .number("duration", p.duration, "Simulated time in units of the diffusion time a^2 / D_0")
      .range(ranges::positive)
      .boolean("until_stable", p.until_stable,
               "Stop earlier once the bond count grows by less than stable_tolerance per stable_window")
      .number("stable_window", p.stable_window, "Window of the until_stable test, in a^2 / D_0")
      .range(ranges::positive)
      .number("stable_tolerance", p.stable_tolerance, "Relative growth of the bond count per window deemed stable")
      .range(ranges::non_negative)
      .integer("samples", p.samples, "Rows of the log (bd_log.csv, msd.csv) over the run")
      .range({1.0, 1e6, false, false})
      .integer("threads", p.threads,
               "Threads of the neighbour search and the pair and bond forces (same bits at any count)")
      .range({1.0, 1024.0, false, false});
}

ConfigSchema bd_options(BdOptions& o) {
  ConfigSchema schema("generate bd", "Brownian-dynamics coagulation with the DLVO potential (docs/bd.md).",
                      "generate_bd");
  add_bd_params(schema, o.bd);
  schema.boolean("msd", o.msd, "Write msd.csv (t, mean squared displacement) for validation")
      .integer("seed", o.seed, "Seed of the random generator");
  add_checkpoint_seconds(schema, o.checkpoint_seconds);
  return schema;
}

ConfigSchema fba_options(FbaOptions& o) {
  ConfigSchema schema("generate fba", "The force-biased algorithm (docs/opal-build.md).", "generate_fba");
  schema.integer("particles", o.particles, "Number of spheres (the box follows from diameter and aspect); or box")
      .numbers("box", o.box, "Box edges LX,LY,LZ (the number of spheres follows from diameter); or particles")
      .unit("m")
      .numbers("aspect", o.aspect, "Box edge ratios with particles")
      .number("diameter", o.diameter, "Diameter of the largest size class")
      .unit("m")
      .range(ranges::positive)
      .numbers("sizes", o.sizes, "Relative diameters of the size classes, e.g. 1,0.5")
      .numbers("number_fractions", o.number_fractions, "Number fractions of the classes (normalized)")
      .numbers("volume_fractions", o.volume_fractions, "Volume fractions of the classes (normalized), instead")
      .text("periodic", o.periodic, "Periodic axes (subset of xyz, or none); walls on the others");
  add_fba_params(schema, o.fba);
  schema.integer("history_every", o.history_every, "Iterations between two rows of the convergence history")
      .range({1.0, ranges::inf, false, true})
      .integer("seed", o.seed, "Seed of the random generator");
  add_checkpoint_seconds(schema, o.checkpoint_seconds);
  return schema;
}

generate::OpalOptions OpalBuildOptions::resolve(const Packing& in, nlohmann::json* pores_report) const {
  require(in.size() >= 1, "particles", 0, ">= 1 in the input packing");
  if ((pore_diameter > 0.0) == (pore_ratio > 0.0))
    fail_input("pore_diameter and pore_ratio: give exactly one of them (> 0)");
  double mean_d = 0;
  for (double r : in.radius) mean_d += 2.0 * r;
  mean_d /= static_cast<double>(in.size());
  const double D = pore_diameter > 0.0 ? pore_diameter : pore_ratio * mean_d;
  require(std::isfinite(D), "pore_diameter", D, "> 0 m");
  generate::OpalOptions o = opal;
  nlohmann::json report;
  if (pores == "fcc") {
    if (pore_count > 0 || pore_fraction > 0.0) fail_input("pore_count / pore_fraction: only with pores = random");
    if (pore_boundary != "walls") fail_input("pore_boundary = " + pore_boundary + ": only with pores = random");
    o.fcc.diameter = D;
    o.fcc.orientation = generate::fcc_orientation_from_name(orientation);
    o.fcc.spacing_ratio = pore_spacing;
    if (!pore_origin.empty()) {
      if (pore_origin.size() != 3)
        fail_input(fmt::format("pore_origin: must be X, Y, Z, got {} values", pore_origin.size()));
      o.fcc.auto_origin = false;
      o.fcc.origin = {pore_origin[0], pore_origin[1], pore_origin[2]};
    }
    const Vec3 per = generate::fcc_pore_period(o.fcc);
    report = {{"arrangement", "fcc"},
              {"orientation", generate::fcc_orientation_name(o.fcc.orientation)},
              {"spacing_ratio", o.fcc.spacing_ratio},
              {"lattice_period_m", {per.x, per.y, per.z}}};
  } else if (pores == "random") {
    if ((pore_count > 0) == (pore_fraction > 0.0))
      fail_input("pore_count and pore_fraction: give exactly one of them with pores = random");
    if (pore_boundary != "walls" && pore_boundary != "periodic")
      fail_input("pore_boundary = " + pore_boundary + ": must be walls or periodic");
    generate::RandomPores rp;
    rp.diameter = D;
    rp.periodic = pore_boundary == "periodic";
    // Periodic pores fill the whole box (they may reach into the substrate slab, as the paper's
    // reach its fixed layer); walled pores stay above the substrate.
    const Box region = rp.periodic ? in.box : generate::random_pore_region(in, o.substrate_layers);
    rp.spacing_ratio = pore_spacing;
    const double v_pore = generate::packed_pore_volume(rp);  // pore_fraction is that of the packed spheres
    if (pore_fraction > 0.0) {
      require(pore_fraction < 0.7, "pore_fraction", pore_fraction, "in (0, 0.7)");
      rp.count = std::max(1L, std::lround(pore_fraction * region.volume() / v_pore));
    } else {
      rp.count = pore_count;
    }
    Random rng(seed);
    o.pores = generate::random_pores(region, rp, rng);
    report = {{"arrangement", "random"},
              {"boundary", pore_boundary},
              {"spacing_ratio", pore_spacing},
              {"count", rp.count},
              {"pore_fraction_of_region", static_cast<double>(rp.count) * v_pore / region.volume()},
              {"region_lo_m", {region.lo.x, region.lo.y, region.lo.z}},
              {"region_length_m", {region.length.x, region.length.y, region.length.z}},
              {"seed", seed}};
  } else {
    fail_input("pores = " + pores + ": must be fcc or random");
  }
  report["diameter_m"] = D;
  report["ratio_to_mean_particle_diameter"] = D / mean_d;
  if (pores_report) *pores_report = std::move(report);
  return o;
}

void add_opal_params(ConfigSchema& schema, generate::OpalOptions& o) {
  schema.number("coating", o.coating_thickness, "Titania coating thickness L_coat (0 = none)")
      .unit("m")
      .range(ranges::non_negative)
      .number("opening_distance_ratio", o.opening_distance_ratio,
              "Coating candidates farther than this x (L_coat + r) from the silica surface stay open")
      .range({0.0, 10.0, true, false})
      .number("substrate_layers", o.substrate_layers,
              "Fixed substrate: particles with z below the bottom + this x mean diameter")
      .range({0.0, 1000.0, false, false})
      .number("bond_cutoff", o.bond_cutoff_ratio,
              "Bond pairs closer than this x (r_i + r_j) (1.75 d for equal particles)")
      .range({1.0, 2.0, false, true})
      .number("bond_radius_ratio", o.bond_radius_ratio,
              "Bond radius / smaller particle radius (recorded for the bond law)")
      .range({0.0, 10.0, true, false})
      .number("silica_density", o.silica_density, "Silica continuum density for the report")
      .unit("kg/m^3")
      .range(ranges::positive)
      .number("titania_density", o.titania_density, "Titania continuum density for the report")
      .unit("kg/m^3")
      .range(ranges::positive)
      .integer("threads", o.threads, "Threads of the bond search")
      .range({1.0, 1024.0, false, false});
}

ConfigSchema opal_build_options(OpalBuildOptions& o) {
  ConfigSchema schema("build opal",
                      "An inverse-opal bonded-particle model from a particle packing (docs/opal-build.md).",
                      "build_opal");
  schema.text("pores", o.pores, "Pore arrangement: fcc (lattice) or random (force-biased pore packing)")
      .number("pore_diameter", o.pore_diameter, "Pore diameter D (or pore_ratio)")
      .unit("m")
      .range(ranges::non_negative)
      .number("pore_ratio", o.pore_ratio, "Pore diameter / mean particle diameter (instead of pore_diameter)")
      .range(ranges::non_negative)
      .text("orientation", o.orientation, "FCC direction along z: 111 or 100")
      .number("pore_spacing", o.pore_spacing,
              "FCC nearest-neighbour pore distance / D (1 = touching, < 1 = wider openings); random pores: "
              "packed as spheres of this x D (pore_fraction is theirs)")
      .range({0.5, 2.0, false, false})
      .numbers("pore_origin", o.pore_origin,
               "A pore lattice point X,Y,Z (default: box corner in x, y; lowest layer just above the substrate)")
      .unit("m")
      .integer("pore_count", o.pore_count, "Random pores: number of pores (or pore_fraction)")
      .range(ranges::non_negative)
      .number("pore_fraction", o.pore_fraction,
              "Random pores: pore volume fraction of the region (above the substrate; the whole box if periodic)")
      .range({0.0, 0.7, false, true})
      .text("pore_boundary", o.pore_boundary,
            "Random pores: walls (inside the box above the substrate) or periodic (the pore packing periodic in z too; "
            "pores cut the faces)")
      .integer("seed", o.seed, "Seed of the random generator (random pores)");
  add_opal_params(schema, o.opal);
  return schema;
}

ConfigSchema shake_options(ShakeOptions& o) {
  ConfigSchema schema("shake", "Monte-Carlo shaking of a hard-sphere packing (docs/scrm.md).", "shake");
  schema.integer("sweeps", o.sweeps, "Global shakes M (each visits every particle once)").range(ranges::non_negative);
  add_shake_params(schema, o.shake);
  schema.integer("seed", o.seed, "Seed of the random generator");
  add_checkpoint_seconds(schema, o.checkpoint_seconds);
  return schema;
}

ConfigSchema bond_options(BondOptions& o) {
  ConfigSchema schema("bond", "Bonds between every pair closer than a cutoff (docs/opal-build.md).", "bond");
  schema
      .text("model", o.model,
            "contact: pairs with d < (1 + eps)(r_i + r_j) (PFC contact bonds, doh-elastic-properties §2.1); elastic: "
            "pairs with d < cutoff_ratio (r_i + r_j) (elastic beam bonds, bpm-inverse-opals §2.1)")
      .number("eps", o.eps, "Contact tolerance of the contact model")
      .range({0.0, 1.0, false, true})
      .number("cutoff_ratio", o.cutoff_ratio,
              "Elastic model: bond pairs closer than this times r_i + r_j (1.75 d for equal spheres)")
      .range({1.0, 2.0, false, true})
      .integer("threads", o.threads, "Threads of the pair search")
      .range({1.0, 1024.0, false, false});
  return schema;
}

}  // namespace packlab::io
