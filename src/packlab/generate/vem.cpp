#include "packlab/generate/vem.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "packlab/analyze/coordination.hpp"
#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/memory.hpp"
#include "packlab/io/options.hpp"

namespace packlab::generate {

namespace {

// "VEMCKP06": checksummed, adapt_threads saved (05: without it).
constexpr std::uint64_t vem_checkpoint_magic = 0x3630504B434D4556ULL;
constexpr int structural_type = particle_type::structural;
constexpr int void_type = particle_type::void_particle;

double sphere_mass(double density, double r) { return density * 4.0 / 3.0 * std::numbers::pi * r * r * r; }

// Stiffest value of LinearContact::stiffness over the contacts a particle of material `a` can
// form with `a` and `b`.
double stiffest_contact(const dem::Material& a, const dem::Material& b) {
  double k = 0.0;
  for (const dem::Material* other : {&a, &b}) {
    k = std::max(k, dem::combine_stiffness(a.normal_stiffness, other->normal_stiffness, dem::StiffnessRule::particle));
    k = std::max(k, dem::combine_stiffness(a.shear_stiffness, other->shear_stiffness, dem::StiffnessRule::particle));
  }
  return k;
}

// The initial random placement: N_S structural centres, then N_V void centres, uniform in the
// box. Radii r_S and r_V0 (the engine is built at full structural size so that its Verlet skin
// and cells fit the final radii; the blow-up then starts from r_S/(m+1)).
Packing initial_packing(const VemParams& p, Random& rng) {
  const double edge = vem_box_edge(p.structural, p.radius, p.phi_s);
  Packing packing;
  packing.box.length = {edge, edge, edge};
  packing.box.periodic = {true, true, true};
  const auto place = [&](long count, double r, int type) {
    for (long i = 0; i < count; ++i) {
      const double x = rng.uniform(0.0, edge);
      const double y = rng.uniform(0.0, edge);
      const double z = rng.uniform(0.0, edge);
      packing.add({x, y, z}, r, type);
    }
  };
  place(p.structural, p.radius, structural_type);
  place(p.voids, p.void_radius_ratio * p.radius, void_type);
  return packing;
}

void write_params(std::ostream& out, const VemParams& p) {
  binary::write(out, p.structural);
  binary::write(out, p.voids);
  binary::write(out, p.phi_s);
  binary::write(out, p.radius);
  binary::write(out, p.blowup_steps);
  binary::write(out, p.void_radius_ratio);
  binary::write(out, p.structural_material);
  binary::write(out, p.void_material);
  binary::write(out, p.contact_eps);
  binary::write(out, p.relax_tolerance);
  binary::write(out, p.relax_overlap);
  binary::write(out, p.relax_max_steps);
  binary::write(out, p.relax_check_interval);
  binary::write(out, p.void_mass_scaling);
  binary::write(out, p.stop_strain_energy);
  binary::write(out, p.max_q);
  binary::write(out, p.stop_min_coordination);
  binary::write(out, static_cast<std::int32_t>(dem::time_step_rule_from_name(p.time_step_rule)));
  binary::write(out, p.time_step_safety);
  binary::write(out, p.skin);
  binary::write(out, p.threads);
  binary::write(out, static_cast<std::uint8_t>(p.adapt_threads));
  binary::write(out, p.seed);
}

VemParams read_params(std::istream& in) {
  VemParams p;
  binary::read(in, p.structural, "structural");
  binary::read(in, p.voids, "voids");
  binary::read(in, p.phi_s, "phi_s");
  binary::read(in, p.radius, "radius");
  binary::read(in, p.blowup_steps, "blowup_steps");
  binary::read(in, p.void_radius_ratio, "void_radius_ratio");
  binary::read(in, p.structural_material, "structural material");
  binary::read(in, p.void_material, "void material");
  binary::read(in, p.contact_eps, "contact_eps");
  binary::read(in, p.relax_tolerance, "relax tolerance");
  binary::read(in, p.relax_overlap, "relax overlap");
  binary::read(in, p.relax_max_steps, "relax max_steps");
  binary::read(in, p.relax_check_interval, "relax check_interval");
  binary::read(in, p.void_mass_scaling, "void_mass_scaling");
  binary::read(in, p.stop_strain_energy, "stop strain_energy");
  binary::read(in, p.max_q, "max_q");
  binary::read(in, p.stop_min_coordination, "stop min_coordination");
  std::int32_t rule = 0;
  binary::read(in, rule, "time_step_rule");
  if (rule < 0 || rule > static_cast<std::int32_t>(dem::TimeStepRule::stiffness_sum))
    fail_input("checkpoint is damaged: unknown time step rule");
  p.time_step_rule = dem::time_step_rule_name(static_cast<dem::TimeStepRule>(rule));
  binary::read(in, p.time_step_safety, "time_step_safety");
  binary::read(in, p.skin, "skin");
  binary::read(in, p.threads, "threads");
  std::uint8_t adapt_threads = 1;
  binary::read(in, adapt_threads, "adapt_threads");
  p.adapt_threads = adapt_threads != 0;
  binary::read(in, p.seed, "seed");
  return p;
}

}  // namespace

double touching_unbalanced_force_ratio(const dem::Engine& engine, const dem::Diagnostics& d) {
  if (d.contacts == 0 || !(d.unbalanced_force_ratio > 0.0)) return 0.0;
  const ParticleStore& P = engine.particles();
  double sum = 0.0;
  long free_count = 0, touching = 0;
  for (std::size_t k = 0; k < P.size(); ++k) {
    if (P.fixed[k]) continue;
    ++free_count;
    const double f = norm(P.force[k]);
    if (f > 0.0) {
      sum += f;
      ++touching;
    }
  }
  if (touching == 0 || sum <= 0.0) return 0.0;
  // The engine's ratio is (sum / free_count) / mean contact force.
  const double mean_contact_force = (sum / static_cast<double>(free_count)) / d.unbalanced_force_ratio;
  return (sum / static_cast<double>(touching)) / mean_contact_force;
}

double vem_box_edge(long structural, double radius, double phi_s) {
  require(structural >= 1, "structural", static_cast<double>(structural), "an integer >= 1");
  require(radius > 0.0 && std::isfinite(radius), "radius", radius, "> 0 m");
  require(phi_s > 0.0 && phi_s < 1.0, "phi_s", phi_s, "in (0, 1)");
  return radius * std::cbrt(4.0 * static_cast<double>(structural) * std::numbers::pi / (3.0 * phi_s));
}

void VemParams::validate() const {
  VemParams copy = *this;
  io::vem_options(copy).validate();  // every declared range, materials included
  // The DEM engine's per-particle state, neighbour list and contact histories: several
  // hundred bytes per particle (DESIGN.md memory notes); 500 is a lower bound.
  const double particles = static_cast<double>(structural) + static_cast<double>(voids);
  require_memory("structural + voids", particles, particles, 500.0);
  dem::validate({structural_material, void_material}, dem::LinearContact::properties);
  require(max_q >= void_radius_ratio && std::isfinite(max_q), "stop.max_q", max_q,
          ">= void_radius_ratio (largest r_V / r_S recorded)");
  if (time_step_rule != "contacts" && time_step_rule != "stiffness_sum")
    fail_input(
        fmt::format("time_step_rule = {}: must be 'stiffness_sum' (PFC's rule, default) or 'contacts' "
                    "(a global step would be set by the tiny voids)",
                    time_step_rule));
  const double edge = vem_box_edge(structural, radius, phi_s);
  const double range = (2.0 * std::max(1.0, max_q) + skin) * radius;
  if (edge < range)
    fail_input(
        fmt::format("stop.max_q = {:g}: the box edge {:.4g} r_S (from structural = {}, phi_s = {:g}, eq. 3) "
                    "must hold 2 max(1, max_q) + skin = {:.4g} r_S; lower max_q or use more particles",
                    max_q, edge / radius, structural, phi_s, range / radius));
}

std::string vem_stop_name(VemStop stop) {
  switch (stop) {
    case VemStop::stage_three:
      return "stage_three";
    case VemStop::max_q:
      return "max_q";
    case VemStop::none:
      break;
  }
  return "none";
}

Packing structural_only(const Packing& packing) {
  Packing out;
  out.box = packing.box;
  for (std::size_t i = 0; i < packing.size(); ++i) {
    if (packing.type[i] != structural_type) continue;
    out.add(packing.position[i], packing.radius[i], structural_type);
    if (!packing.velocity.empty()) out.velocity.push_back(packing.velocity[i]);
    if (!packing.angular_velocity.empty()) out.angular_velocity.push_back(packing.angular_velocity[i]);
  }
  return out;
}

double structural_coordination(const Packing& packing, double eps) {
  const Packing s = structural_only(packing);
  if (s.size() == 0) return 0.0;
  analyze::Coordination coordination(eps);
  coordination.compute(s);
  return coordination.mean();
}

Vem::Vem(const VemParams& params, ResumeTag) : params_(params), rng_(params.seed) { params_.validate(); }

Vem::Vem(const VemParams& params) : Vem(params, ResumeTag{}) { build_engine(); }

Vem::~Vem() = default;

dem::EngineConfig Vem::engine_config() const {
  dem::EngineConfig c;
  c.contact_law = "linear";
  c.types = {params_.structural_material, params_.void_material};
  c.stiffness_rule = dem::StiffnessRule::particle;
  c.time_step_rule = dem::time_step_rule_from_name(params_.time_step_rule);
  c.time_step_safety = params_.time_step_safety;
  c.skin_ratio = params_.skin / std::max(1.0, params_.void_radius_ratio);
  c.threads = params_.threads;
  c.adapt_threads = params_.adapt_threads;
  // The structure is a gas until it jams: its particles diffuse out of their sorted order
  // (dem/resort.cpp).
  c.resort_particles = true;
  return c;
}

// Draws the placement from rng_ and builds the engine at the start of the blow-up.
void Vem::build_engine() {
  const Packing start = initial_packing(params_, rng_);
  engine_ = std::make_unique<dem::Engine>(start, engine_config());
  engine_->set_radius_of_type(structural_type, structural_radius());
  apply_mass_scaling();
}

double Vem::structural_radius() const {
  const int m = params_.blowup_steps;
  // Exactly r_S after the m-th step (no round-off from (m+1) * r_S/(m+1)).
  return blowup_done_ >= m ? params_.radius
                           : static_cast<double>(blowup_done_ + 1) * params_.radius / static_cast<double>(m + 1);
}

double Vem::void_radius() const { return static_cast<double>(cycle_ + 1) * params_.void_radius_ratio * params_.radius; }

double Vem::void_mass_floor() const {
  if (params_.void_mass_scaling <= 0.0) return 0.0;
  const double m_s = sphere_mass(params_.structural_material.density, structural_radius());
  const double k_s = stiffest_contact(params_.structural_material, params_.void_material);
  const double k_v = stiffest_contact(params_.void_material, params_.structural_material);
  return params_.void_mass_scaling * m_s * k_v / k_s;
}

// Void mass max(m_V, c m_S k_V / k_S), moment of inertia 2/5 m r^2. The engine recomputes
// true masses whenever a radius changes or a state is loaded, so this runs after each.
void Vem::apply_mass_scaling() {
  const double floor = void_mass_floor();
  if (floor <= 0.0) return;
  ParticleStore& P = engine_->particles();
  for (std::size_t k = 0; k < P.size(); ++k) {
    if (P.type[k] != void_type || P.fixed[k]) continue;
    const double r = P.radius[k];
    const double m = std::max(sphere_mass(params_.void_material.density, r), floor);
    P.mass[k] = m;
    P.inverse_mass[k] = 1.0 / m;
    P.inverse_inertia[k] = 1.0 / sphere_inertia(m, r);
  }
  engine_->masses_changed();
}

void Vem::start_relaxation() {
  relaxing_ = true;
  relax_done_ = 0;
  relax_converged_ = false;
  relax_last_ = dem::Diagnostics{};
}

void Vem::finish_relaxation() {
  relaxing_ = false;
  if (!relax_converged_) ++limited_relaxations_;
  if (stage_ == VemStage::expansion) record_row();
}

void Vem::record_row() {
  VemRow row;
  row.cycle = cycle_;
  row.q = void_radius() / params_.radius;
  row.cn = structural_coordination(engine_->packing(), params_.contact_eps);
  row.phi_total = params_.phi_s * (1.0 + row.q * row.q * row.q * params_.number_ratio());
  row.strain_energy = relax_last_.strain_energy;
  row.kinetic_energy = relax_last_.kinetic_energy;
  row.steps = relax_done_;
  row.unbalanced_force_ratio = relax_last_.unbalanced_force_ratio;
  row.converged = relax_converged_;
  curve_.push_back(row);
  if (on_row) on_row(row);
  const double scale = static_cast<double>(params_.structural) * params_.structural_material.normal_stiffness *
                       params_.radius * params_.radius;
  const double next_q = static_cast<double>(cycle_ + 2) * params_.void_radius_ratio;
  if (row.strain_energy / scale >= params_.stop_strain_energy && row.cn >= params_.stop_min_coordination) {
    stop_ = VemStop::stage_three;
    stage_ = VemStage::finished;
  } else if (next_q > params_.max_q * (1.0 + 1e-12)) {
    stop_ = VemStop::max_q;
    stage_ = VemStage::finished;
  }
}

bool Vem::run(long max_steps) {
  const auto t0 = std::chrono::steady_clock::now();
  long budget = max_steps;
  const long interval = params_.relax_check_interval;
  const long limit = params_.relax_max_steps;
  while (stage_ != VemStage::finished && (max_steps < 0 || budget > 0)) {
    if (!relaxing_) {
      if (stage_ == VemStage::blowup) {
        if (blowup_done_ == params_.blowup_steps) {
          stage_ = VemStage::expansion;
          record_row();  // q = r_V0 / r_S, after the last blow-up relaxation
          continue;
        }
        ++blowup_done_;
        engine_->set_radius_of_type(structural_type, structural_radius());
      } else {
        ++cycle_;
        engine_->set_radius_of_type(void_type, void_radius());
      }
      apply_mass_scaling();
      start_relaxation();
      continue;
    }
    // One relaxation, in pieces that end at a check or at the budget: measured steps at every
    // multiple of the check interval and at the last allowed step.
    if (relax_done_ % interval == 0 || relax_done_ == limit - 1) {
      const dem::Diagnostics d = engine_->step_measured();
      ++relax_done_;
      ++total_steps_;
      --budget;
      relax_last_ = d;
      relax_last_.unbalanced_force_ratio = touching_unbalanced_force_ratio(*engine_, d);
      if (on_check) on_check(relax_last_);
      if ((params_.relax_tolerance > 0.0 && relax_last_.unbalanced_force_ratio < params_.relax_tolerance) ||
          (params_.relax_overlap > 0.0 && relax_last_.max_overlap_ratio < params_.relax_overlap)) {
        relax_converged_ = true;
        finish_relaxation();
      } else if (relax_done_ >= limit) {
        finish_relaxation();
      }
      continue;
    }
    const long next_check = std::min((relax_done_ / interval + 1) * interval, limit - 1);
    long n = next_check - relax_done_;
    if (max_steps >= 0) n = std::min(n, budget);
    engine_->run(n);
    relax_done_ += n;
    total_steps_ += n;
    budget -= n;
  }
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finished();
}

void Vem::save_checkpoint(std::ostream& out) const {
  binary::write(out, vem_checkpoint_magic);
  binary::write_checked(out, [&](std::ostream& section) { save_state(section); });
  if (!out) fail_input("checkpoint: write failed");
}

void Vem::save_state(std::ostream& out) const {
  write_params(out, params_);
  binary::write_random(out, rng_);
  binary::write(out, static_cast<std::int32_t>(stage_));
  binary::write(out, static_cast<std::int32_t>(stop_));
  binary::write(out, blowup_done_);
  binary::write(out, cycle_);
  binary::write(out, static_cast<std::uint8_t>(relaxing_));
  binary::write(out, relax_done_);
  // The fields of the last relaxation check that a row uses (not the whole Diagnostics struct,
  // so that checkpoints survive additions to it).
  binary::write(out, relax_last_.strain_energy);
  binary::write(out, relax_last_.kinetic_energy);
  binary::write(out, relax_last_.unbalanced_force_ratio);
  binary::write(out, relax_last_.max_overlap_ratio);
  binary::write(out, static_cast<std::uint8_t>(relax_converged_));
  binary::write(out, total_steps_);
  binary::write(out, limited_relaxations_);
  binary::write(out, seconds_);
  binary::write_vector(out, curve_);
  engine_->save_state(out);
}

std::unique_ptr<Vem> Vem::resume(std::istream& checkpoint, int threads, std::optional<bool> adapt_threads) {
  std::uint64_t magic = 0;
  binary::read(checkpoint, magic, "header");
  binary::require_header(magic, vem_checkpoint_magic, "checkpoint: not a packlab VEM checkpoint");
  std::istringstream in = binary::read_checked(checkpoint, "the VEM state");
  VemParams params = read_params(in);
  if (threads > 0) params.threads = threads;
  if (adapt_threads) params.adapt_threads = *adapt_threads;
  std::unique_ptr<Vem> vem(new Vem(params, ResumeTag{}));
  binary::read_random(in, vem->rng_);
  std::int32_t stage = 0, stop = 0;
  std::uint8_t relaxing = 0, converged = 0;
  binary::read(in, stage, "stage");
  binary::read(in, stop, "stop reason");
  if (stage < 0 || stage > 2 || stop < 0 || stop > 2) fail_input("checkpoint is damaged: unknown VEM stage");
  binary::read(in, vem->blowup_done_, "blow-up steps");
  binary::read(in, vem->cycle_, "cycle");
  binary::read(in, relaxing, "relaxation flag");
  binary::read(in, vem->relax_done_, "relaxation steps");
  binary::read(in, vem->relax_last_.strain_energy, "relaxation diagnostics");
  binary::read(in, vem->relax_last_.kinetic_energy, "relaxation diagnostics");
  binary::read(in, vem->relax_last_.unbalanced_force_ratio, "relaxation diagnostics");
  binary::read(in, vem->relax_last_.max_overlap_ratio, "relaxation diagnostics");
  binary::read(in, converged, "relaxation state");
  binary::read(in, vem->total_steps_, "total steps");
  binary::read(in, vem->limited_relaxations_, "limited relaxations");
  binary::read(in, vem->seconds_, "seconds");
  binary::read_vector(in, vem->curve_, "CN(q) curve");
  if (vem->blowup_done_ < 0 || vem->blowup_done_ > params.blowup_steps || vem->cycle_ < 0)
    fail_input("checkpoint is damaged: VEM counters out of range");
  vem->stage_ = static_cast<VemStage>(stage);
  vem->stop_ = static_cast<VemStop>(stop);
  vem->relaxing_ = relaxing != 0;
  vem->relax_converged_ = converged != 0;
  // The engine is built as at the start (same placement from the seed), then takes the saved state.
  Random placement(params.seed);
  const Packing start = initial_packing(params, placement);
  vem->engine_ = std::make_unique<dem::Engine>(start, vem->engine_config());
  vem->engine_->load_state(in);
  vem->apply_mass_scaling();
  return vem;
}

Packing Vem::packing() const {
  Packing p = engine_->packing();
  p.velocity.clear();
  p.angular_velocity.clear();
  return p;
}

Packing Vem::structural_packing() const { return structural_only(packing()); }

}  // namespace packlab::generate
