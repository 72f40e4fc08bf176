#include "packlab/dem/engine.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <type_traits>

#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/spatial_sort.hpp"
#include "packlab/dem/local_damping.hpp"

namespace packlab::dem {

std::vector<std::string> contact_law_names() { return {LinearContact::name, HertzMindlin::name}; }

TimeStepRule time_step_rule_from_name(const std::string& name) {
  if (name == "global") return TimeStepRule::global;
  if (name == "contacts") return TimeStepRule::contacts;
  if (name == "stiffness_sum") return TimeStepRule::stiffness_sum;
  fail_input(fmt::format("time_step_rule = {}: must be 'global', 'contacts' or 'stiffness_sum'", name));
}

std::string time_step_rule_name(TimeStepRule rule) {
  switch (rule) {
    case TimeStepRule::global: return "global";
    case TimeStepRule::contacts: return "contacts";
    case TimeStepRule::stiffness_sum: return "stiffness_sum";
  }
  return "global";
}

namespace {

template <class Law>
ContactModel<Law> make_model(const std::vector<TypeParams>& types, int type_count, StiffnessRule rule) {
  ContactModel<Law> model;
  model.type_count = type_count;
  model.pair_params.resize(static_cast<std::size_t>(type_count) * type_count);
  auto of = [&](int t) -> const TypeParams& { return types.size() == 1 ? types[0] : types[t]; };
  for (int a = 0; a < type_count; ++a)
    for (int b = 0; b < type_count; ++b) model.pair_params[a * type_count + b] = Law::mix(of(a), of(b), rule);
  return model;
}

ContactModels make_models(const std::string& name, const std::vector<TypeParams>& types, int type_count,
                          StiffnessRule rule) {
  if (name == LinearContact::name) return make_model<LinearContact>(types, type_count, rule);
  if (name == HertzMindlin::name) {
    for (std::size_t t = 0; t < types.size(); ++t) {
      const std::string key = fmt::format("type {} ", t);
      require(types[t].youngs_modulus > 0.0 && std::isfinite(types[t].youngs_modulus), key + "youngs_modulus",
              types[t].youngs_modulus, "> 0 Pa for hertz_mindlin");
      require(types[t].poisson_ratio > -1.0 && types[t].poisson_ratio < 0.5, key + "poisson_ratio",
              types[t].poisson_ratio, "in (-1, 0.5)");
      require(types[t].restitution > 0.0 && types[t].restitution <= 1.0, key + "restitution", types[t].restitution,
              "in (0, 1]");
      require(types[t].rolling_friction >= 0.0, key + "rolling_friction", types[t].rolling_friction, ">= 0");
    }
    return make_model<HertzMindlin>(types, type_count, rule);
  }
  fail_input(fmt::format("contact_law = {}: must be one of: {}", name, fmt::join(contact_law_names(), ", ")));
}

}  // namespace

Engine::Engine(const Packing& packing, const EngineConfig& config) : packing_(packing), config_(config) {
  packing_.validate();
  validate(config_.types);
  require(config_.time_step >= 0.0 && std::isfinite(config_.time_step), "time_step", config_.time_step,
          ">= 0 s (0 = automatic)");
  require(config_.time_step_safety > 0.0 && config_.time_step_safety <= 1.0, "time_step_safety",
          config_.time_step_safety, "in (0, 1]");
  require(config_.skin_ratio > 0.0 && config_.skin_ratio <= 10.0, "skin_ratio", config_.skin_ratio,
          "in (0, 10]");
  require(config_.max_time_step >= 0.0 && std::isfinite(config_.max_time_step), "max_time_step",
          config_.max_time_step, ">= 0 s (0 = automatic)");
  require(config_.threads >= 0, "threads", config_.threads, ">= 0 (0 = all cores)");

  const std::size_t n = packing_.size();
  int type_count = 1;
  for (int t : packing_.type) type_count = std::max(type_count, t + 1);
  if (config_.types.size() > 1 && static_cast<int>(config_.types.size()) < type_count)
    fail_input(fmt::format("the packing has particle type {} but parameters were given for {} types",
                           type_count - 1, config_.types.size()));

  double r_max = 0.0;
  for (double r : packing_.radius) r_max = std::max(r_max, r);
  original_index_ = spatial_order(packing_.box, packing_.position, 2.0 * r_max * (1.0 + config_.skin_ratio));
  particles_.resize(n);
  damping_.resize(n);
  density_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = static_cast<std::size_t>(original_index_[k]);
    const TypeParams& tp = params_of_type(packing_.type[i]);
    const double r = packing_.radius[i];
    const double density = packing_.density.empty() ? tp.density : packing_.density[i];
    particles_.position[k] = packing_.position[i];
    particles_.velocity[k] = packing_.velocity.empty() ? Vec3{} : packing_.velocity[i];
    particles_.angular_velocity[k] = packing_.angular_velocity.empty() ? Vec3{} : packing_.angular_velocity[i];
    particles_.radius[k] = r;
    particles_.type[k] = packing_.type[i];
    particles_.fixed[k] = packing_.fixed.empty() ? 0 : packing_.fixed[i];
    density_[k] = density;
    update_mass(k);
    if (particles_.fixed[k]) particles_.velocity[k] = particles_.angular_velocity[k] = Vec3{};
    damping_[k] = tp.damping;
  }

  model_ = make_models(config_.contact_law, config_.types, type_count, config_.stiffness_rule);

  // Bonds, mapped to the engine's particle order.
  wraps_.assign(n, {0, 0, 0});
  {
    std::vector<int> internal(n);
    for (std::size_t k = 0; k < n; ++k) internal[static_cast<std::size_t>(original_index_[k])] = static_cast<int>(k);
    const Bonds& in = packing_.bonds;
    bool any_intact = false;
    for (std::size_t b = 0; b < in.size(); ++b) {
      bonds_.i.push_back(internal[static_cast<std::size_t>(in.i[b])]);
      bonds_.j.push_back(internal[static_cast<std::size_t>(in.j[b])]);
      bonds_.image.push_back(in.image[b]);
      bonds_.material.push_back(in.material[b]);
      bonds_.rest_length.push_back(in.rest_length[b]);
      bonds_.state.push_back(in.state[b] == 0 ? 0 : 1);
      bonds_.pair.push_back(-1);
      any_intact = any_intact || in.state[b] == 0;
      if (in.state[b] != 0) ++broken_bonds_;
    }
    if (config_.bond_law == ContactBond::name) {
      bonds_.history = std::vector<ContactBond::State>(in.size());
    } else if (config_.bond_law == ElasticBond::name) {
      bonds_.history = std::vector<ElasticBond::State>(in.size());
    } else {
      fail_input(fmt::format("bond_law = {}: must be '{}' or '{}'", config_.bond_law, ContactBond::name,
                             ElasticBond::name));
    }
    if (any_intact) {
      const std::size_t materials = config_.bond_law == ContactBond::name ? config_.bond_materials.size()
                                                                          : config_.elastic_bond_materials.size();
      if (materials == 0)
        fail_input(fmt::format("the packing has bonds but no parameters were given for the '{}' bond law",
                               config_.bond_law));
      for (std::size_t m = 0; m < config_.bond_materials.size(); ++m) {
        const auto& bp = config_.bond_materials[m];
        const std::string key = fmt::format("bond material {} ", m);
        require(bp.normal_stiffness > 0.0 && std::isfinite(bp.normal_stiffness), key + "normal_stiffness",
                bp.normal_stiffness, "> 0 N/m");
        require(bp.shear_stiffness >= 0.0 && std::isfinite(bp.shear_stiffness), key + "shear_stiffness",
                bp.shear_stiffness, ">= 0 N/m");
        require(bp.normal_strength >= 0.0, key + "normal_strength", bp.normal_strength, ">= 0 N (inf: never)");
        require(bp.shear_strength >= 0.0, key + "shear_strength", bp.shear_strength, ">= 0 N (inf: never)");
      }
      for (std::size_t m = 0; m < config_.elastic_bond_materials.size(); ++m) {
        const auto& bp = config_.elastic_bond_materials[m];
        const std::string key = fmt::format("elastic bond material {} ", m);
        require(bp.youngs_modulus > 0.0 && std::isfinite(bp.youngs_modulus), key + "youngs_modulus",
                bp.youngs_modulus, "> 0 Pa");
        require(bp.poisson_ratio > -1.0 && bp.poisson_ratio < 0.5, key + "poisson_ratio", bp.poisson_ratio,
                "in (-1, 0.5)");
        require(bp.normal_strength > 0.0, key + "normal_strength", bp.normal_strength, "> 0 Pa (inf: never)");
        require(bp.shear_strength > 0.0, key + "shear_strength", bp.shear_strength, "> 0 Pa (inf: never)");
        require(bp.radius_ratio > 0.0 && bp.radius_ratio <= 1.0, key + "radius_ratio", bp.radius_ratio, "in (0, 1]");
        require(bp.relaxation_time > 0.0, key + "relaxation_time", bp.relaxation_time, "> 0 s");
      }
      for (std::size_t b = 0; b < in.size(); ++b) {
        if (materials > 1 && (in.material[b] < 0 || static_cast<std::size_t>(in.material[b]) >= materials))
          fail_input(fmt::format("bond {} has material {}: parameters were given for materials 0..{}", b,
                                 in.material[b], materials - 1));
        if (config_.bond_law == ElasticBond::name && !(in.rest_length[b] > 0.0))
          fail_input(fmt::format("bond {} has rest length {:g}: must be > 0 m for elastic bonds", b,
                                 in.rest_length[b]));
      }
    }
  }
  threads_ = config_.threads > 0 ? config_.threads : omp_get_max_threads();
  thread_force_.assign(threads_, {});
  thread_torque_.assign(threads_, {});
  thread_totals_.assign(threads_, {});
  thread_wall_force_.assign(threads_, {});
  thread_breaks_.assign(threads_, {});

  neighbors_.set_skin(config_.skin_ratio * r_max);
  masses_changed();
  if (config_.time_step > 0.0)
    dt_ = config_.time_step;
  else if (config_.time_step_rule != TimeStepRule::global)
    dt_ = time_step_cap_;
  else
    dt_ = critical_time_step();
  if (!(dt_ > 0.0) || !std::isfinite(dt_)) fail_input("time step: could not be determined (no particles?)");
  refresh_neighbors();
}

const TypeParams& Engine::params_of_type(int type) const {
  return config_.types.size() == 1 ? config_.types[0] : config_.types[type];
}

double Engine::critical_time_step() const {
  double dt = std::numeric_limits<double>::infinity();
  std::visit(
      [&](const auto& model) {
        using Law = std::decay_t<decltype(model.law)>;
        for (std::size_t i = 0; i < particles_.size(); ++i) {
          if (particles_.fixed[i]) continue;
          const int t = particles_.type[i];
          const double k = Law::stiffness(model.pair_params[t * model.type_count + t], particles_.radius[i]);
          if (k > 0.0) dt = std::min(dt, std::sqrt(particles_.mass[i] / k));
        }
      },
      model_);
  with_bond_law([&](auto law) {
    using BondLaw = decltype(law);
    const double inf = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < bonds_.i.size(); ++b) {
      if (bonds_.state[b] != 0) continue;
      const auto i = static_cast<std::size_t>(bonds_.i[b]), j = static_cast<std::size_t>(bonds_.j[b]);
      const double m = std::min(particles_.fixed[i] ? inf : particles_.mass[i], particles_.fixed[j] ? inf : particles_.mass[j]);
      const double k = BondLaw::stiffness(bond_params<BondLaw>(b), particles_.radius[i], particles_.radius[j],
                                          bonds_.rest_length[b]);
      if (std::isfinite(m)) dt = std::min(dt, std::sqrt(m / k));
    }
  });
  return config_.time_step_safety * dt;
}

void Engine::update_mass(std::size_t k) {
  const double r = particles_.radius[k];
  particles_.mass[k] = density_[k] * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  particles_.inertia[k] = 0.4 * particles_.mass[k] * r * r;
  particles_.inverse_mass[k] = particles_.fixed[k] ? 0.0 : 1.0 / particles_.mass[k];
  particles_.inverse_inertia[k] = particles_.fixed[k] ? 0.0 : 1.0 / particles_.inertia[k];
}

double Engine::heaviest_particle_time_step() const {
  double dt = 0.0;
  std::visit(
      [&](const auto& model) {
        using Law = std::decay_t<decltype(model.law)>;
        for (std::size_t i = 0; i < particles_.size(); ++i) {
          const int t = particles_.type[i];
          const double k = Law::stiffness(model.pair_params[t * model.type_count + t], particles_.radius[i]);
          if (k > 0.0) dt = std::max(dt, std::sqrt(particles_.mass[i] / k));
        }
      },
      model_);
  return config_.time_step_safety * dt;
}

void Engine::set_radius_of_type(int type, double radius) {
  require(radius > 0.0 && std::isfinite(radius), "radius", radius, "> 0 m");
  for (std::size_t k = 0; k < particles_.size(); ++k)
    if (particles_.type[k] == type) {
      particles_.radius[k] = radius;
      update_mass(k);
    }
  masses_changed();
}

void Engine::set_radii(const std::vector<double>& radius) {
  if (radius.size() != particles_.size())
    fail_input(fmt::format("set_radii: {} radii for {} particles", radius.size(), particles_.size()));
  for (std::size_t k = 0; k < particles_.size(); ++k) {
    const double r = radius[static_cast<std::size_t>(original_index_[k])];
    require(r > 0.0 && std::isfinite(r), "radius", r, "> 0 m");
    particles_.radius[k] = r;
    update_mass(k);
  }
  masses_changed();
}

void Engine::masses_changed() {
  time_step_cap_ = config_.max_time_step > 0.0 ? config_.max_time_step : heaviest_particle_time_step();
}

ContactGeometry Engine::pair_geometry(std::size_t i, std::size_t j, const Vec3& d, double distance) const {
  const auto& P = particles_;
  ContactGeometry g;
  g.normal = d * (1.0 / distance);
  g.overlap = P.radius[i] + P.radius[j] - distance;
  g.branch_i = P.radius[i] - 0.5 * g.overlap;
  g.branch_j = P.radius[j] - 0.5 * g.overlap;
  g.relative_velocity =
      P.velocity[j] - P.velocity[i] - cross(g.branch_j * P.angular_velocity[j] + g.branch_i * P.angular_velocity[i], g.normal);
  g.mean_spin = 0.5 * (P.angular_velocity[i] + P.angular_velocity[j]);
  g.dt = dt_;
  g.radius_i = P.radius[i];
  g.radius_j = P.radius[j];
  // Two fixed particles: no relative motion to damp (0, not infinity, so no NaN reaches them).
  const double inverse_sum = P.inverse_mass[i] + P.inverse_mass[j];
  g.effective_mass = inverse_sum > 0.0 ? 1.0 / inverse_sum : 0.0;
  g.spin_i = P.angular_velocity[i];
  g.spin_j = P.angular_velocity[j];
  g.relative_spin = P.angular_velocity[j] - P.angular_velocity[i];
  g.time = time_;
  return g;
}

ContactGeometry Engine::wall_geometry(std::size_t k, const Wall& wall, double distance) const {
  const auto& P = particles_;
  // The particle is i, the wall j: the normal points from the particle into the wall.
  ContactGeometry g;
  g.normal = -wall.normal;
  g.overlap = P.radius[k] - distance;
  g.branch_i = distance;
  g.branch_j = 0.0;
  g.relative_velocity = wall.velocity - P.velocity[k] - cross(g.branch_i * P.angular_velocity[k], g.normal);
  g.mean_spin = 0.5 * P.angular_velocity[k];
  g.dt = dt_;
  g.radius_i = P.radius[k];
  g.radius_j = 1e12 * P.radius[k];  // a plane: R* = r
  g.effective_mass = P.mass[k];
  g.spin_i = P.angular_velocity[k];
  g.spin_j = Vec3{};
  g.time = time_;
  return g;
}

void Engine::set_time_step(double dt) {
  require(dt > 0.0 && std::isfinite(dt), "time_step", dt, "> 0 s");
  dt_ = dt;
}

void Engine::refresh_neighbors() {
  neighbors_.build(packing_.box, particles_.position, particles_.radius, threads_, &wraps_);
  std::visit(
      [&](auto& model) {
        using History = typename std::decay_t<decltype(model.law)>::History;
        std::vector<History> remapped(neighbors_.pair_count(), History{});
        const auto& previous = neighbors_.previous_index();
        for (std::size_t p = 0; p < remapped.size(); ++p)
          if (previous[p] >= 0 && static_cast<std::size_t>(previous[p]) < model.history.size())
            remapped[p] = model.history[previous[p]];
        model.history.swap(remapped);
      },
      model_);
  mark_bonded_pairs();
}

std::array<int, 3> Engine::bond_image_now(std::size_t b) const {
  const auto& wi = wraps_[static_cast<std::size_t>(bonds_.i[b])];
  const auto& wj = wraps_[static_cast<std::size_t>(bonds_.j[b])];
  return {bonds_.image[b][0] + wj[0] - wi[0], bonds_.image[b][1] + wj[1] - wi[1], bonds_.image[b][2] + wj[2] - wi[2]};
}

void Engine::mark_bonded_pairs() {
  pair_bonded_.assign(neighbors_.pair_count(), 0);
  const auto& partner = neighbors_.partner();
  const auto& image = neighbors_.image();
  for (std::size_t b = 0; b < bonds_.i.size(); ++b) {
    bonds_.pair[b] = -1;
    if (bonds_.state[b] != 0) continue;
    auto s = bond_image_now(b);
    int i = bonds_.i[b], j = bonds_.j[b];
    if (j < i) {
      std::swap(i, j);
      s = {-s[0], -s[1], -s[2]};
    }
    if (std::abs(s[0]) > 1 || std::abs(s[1]) > 1 || std::abs(s[2]) > 1) continue;  // out of range
    const int code = image_code(s[0], s[1], s[2]);
    for (int p = neighbors_.first(i); p < neighbors_.first(i + 1); ++p)
      if (partner[p] == j && image[p] == code) {
        bonds_.pair[b] = p;
        pair_bonded_[p] = 1;
      }
  }
}

template <class BondLaw>
const std::vector<typename BondLaw::Params>& Engine::bond_materials() const {
  if constexpr (std::is_same_v<BondLaw, ContactBond>)
    return config_.bond_materials;
  else
    return config_.elastic_bond_materials;
}

template <class BondLaw>
const typename BondLaw::Params& Engine::bond_params(std::size_t b) const {
  const auto& materials = bond_materials<BondLaw>();
  return materials.size() == 1 ? materials[0] : materials[static_cast<std::size_t>(bonds_.material[b])];
}

template <class F>
void Engine::with_bond_law(F&& f) const {
  if (bonds_.i.empty()) return;
  if (std::holds_alternative<std::vector<ContactBond::State>>(bonds_.history))
    f(ContactBond{});
  else
    f(ElasticBond{});
}

std::size_t Engine::add_wall(const Wall& wall) {
  const double length = norm(wall.normal);
  if (!(length > 0.0) || !std::isfinite(length)) fail_input("wall normal: must be a nonzero finite vector");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(wall.point[a]) || !std::isfinite(wall.velocity[a]))
      fail_input("wall point and velocity: must be finite");
  static_assert(std::is_same_v<LinearContact::History, Vec3> && std::is_same_v<HertzMindlin::History, Vec3>,
                "wall contacts keep a Vec3 history per particle");
  Wall w = wall;
  w.normal *= 1.0 / length;
  // Re-layout the per-particle wall histories for one more wall.
  const std::size_t n = particles_.size(), walls = walls_.size();
  std::vector<Vec3> history(n * (walls + 1));
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t m = 0; m < walls; ++m) history[k * (walls + 1) + m] = wall_history_[k * walls + m];
  wall_history_.swap(history);
  walls_.push_back(w);
  wall_force_.push_back(Vec3{});
  return walls_.size() - 1;
}

template <class Law, bool Measure>
void Engine::wall_forces(ContactModel<Law>& model, int thread, Vec3* force, Vec3* torque, double* stiffness,
                         Totals& local) {
  const std::size_t n = particles_.size(), walls = walls_.size();
  const std::size_t begin = n * thread / threads_, end = n * (thread + 1) / threads_;
  auto& wall_force = thread_wall_force_[thread];
  wall_force.assign(walls, Vec3{});
  const auto& P = particles_;
  for (std::size_t k = begin; k < end; ++k) {
    for (std::size_t m = 0; m < walls; ++m) {
      const Wall& wall = walls_[m];
      const double distance = dot(P.position[k] - wall.point, wall.normal);
      Vec3& history = wall_history_[k * walls + m];
      if (distance >= P.radius[k]) {
        history = Vec3{};
        continue;
      }
      const ContactGeometry g = wall_geometry(k, wall, distance);
      const int t = P.type[k];
      const auto& params = model.pair_params[t * model.type_count + t];
      const PairForce f = Law::evaluate(g, params, history);
      force[k] -= f.force_on_j;
      torque[k] += f.torque_i;
      wall_force[m] += f.force_on_j;
      local.max_stiffness_over_mass = std::max(local.max_stiffness_over_mass, f.stiffness * P.inverse_mass[k]);
      if (stiffness) stiffness[k] += f.stiffness;
      if constexpr (Measure) {
        ++local.contacts;
        local.contact_force_sum += norm(f.force_on_j);
        local.strain_energy += f.energy;
      }
    }
  }
}

ContactForces Engine::contact_forces() const {
  ContactForces out;
  const auto& P = particles_;
  const std::size_t n = P.size();
  // The elastic forces as stored: no increment of the histories (dt = 0) and no damping
  // (no relative motion).
  auto as_stored = [](ContactGeometry g) {
    g.dt = 0.0;
    g.relative_velocity = g.mean_spin = g.spin_i = g.spin_j = g.relative_spin = Vec3{};
    return g;
  };
  auto push = [&](int i, int j, int kind, const Vec3& branch, const Vec3& force) {
    out.i.push_back(i);
    out.j.push_back(j);
    out.kind.push_back(kind);
    out.branch.push_back(branch);
    out.force.push_back(force);
  };
  std::visit(
      [&](const auto& model) {
        using Law = std::decay_t<decltype(model.law)>;
        for (std::size_t i = 0; i < n; ++i)
          for (int p = neighbors_.first(static_cast<int>(i)); p < neighbors_.first(static_cast<int>(i) + 1); ++p) {
            if (!pair_bonded_.empty() && pair_bonded_[p]) continue;
            const std::size_t j = static_cast<std::size_t>(neighbors_.partner()[p]);
            const Vec3 d = P.position[j] + neighbors_.image_offset(neighbors_.image()[p]) - P.position[i];
            const double rsum = P.radius[i] + P.radius[j];
            if (norm2(d) >= rsum * rsum) continue;
            auto history = model.history[p];
            const PairForce f = Law::evaluate(as_stored(pair_geometry(i, j, d, norm(d))),
                                              model.pair_params[P.type[i] * model.type_count + P.type[j]], history);
            push(original_index_[i], original_index_[j], ContactForces::contact, d, f.force_on_j);
          }
        for (std::size_t m = 0; m < walls_.size(); ++m)
          for (std::size_t k = 0; k < n; ++k) {
            const double distance = dot(P.position[k] - walls_[m].point, walls_[m].normal);
            if (distance >= P.radius[k]) continue;
            const ContactGeometry g = as_stored(wall_geometry(k, walls_[m], distance));
            auto history = wall_history_[k * walls_.size() + m];
            const int t = P.type[k];
            const PairForce f = Law::evaluate(g, model.pair_params[t * model.type_count + t], history);
            push(original_index_[k], -1 - static_cast<int>(m), ContactForces::wall, distance * g.normal, f.force_on_j);
          }
      },
      model_);
  with_bond_law([&](auto law) {
    using BondLaw = decltype(law);
    const auto& histories = std::get<std::vector<typename BondLaw::State>>(bonds_.history);
    for (std::size_t b = 0; b < bonds_.i.size(); ++b) {
      if (bonds_.state[b] != 0) continue;
      const std::size_t i = static_cast<std::size_t>(bonds_.i[b]), j = static_cast<std::size_t>(bonds_.j[b]);
      const Vec3 d = P.position[j] + packing_.box.shift_vector(bond_image_now(b)) - P.position[i];
      auto history = histories[b];
      ContactGeometry g = as_stored(pair_geometry(i, j, d, norm(d)));
      g.rest_length = bonds_.rest_length[b];
      const BondForce f = BondLaw::evaluate(g, bond_params<BondLaw>(b), history);
      push(original_index_[i], original_index_[j], ContactForces::bond, d, f.force_on_j);
    }
  });
  return out;
}

std::vector<std::array<double, 9>> particle_stress(const ContactForces& forces, const Packing& packing) {
  std::vector<std::array<double, 9>> stress(packing.size(), std::array<double, 9>{});
  auto add = [&](int particle, const Vec3& l, const Vec3& f, double weight) {
    auto& s = stress[static_cast<std::size_t>(particle)];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) s[3 * a + b] += weight * l[a] * f[b];
  };
  for (std::size_t c = 0; c < forces.size(); ++c) {
    if (forces.j[c] >= 0) {
      add(forces.i[c], forces.branch[c], -forces.force[c], 0.5);  // i: branch to j, force -F
      add(forces.j[c], -forces.branch[c], forces.force[c], 0.5);  // j: branch to i, force F
    } else {
      add(forces.i[c], forces.branch[c], -forces.force[c], 1.0);  // wall: branch to contact point
    }
  }
  for (std::size_t k = 0; k < packing.size(); ++k) {
    const double r = packing.radius[k];
    const double volume = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    for (double& v : stress[k]) v /= volume;
  }
  return stress;
}

std::vector<double> Engine::bond_strains() const {
  std::vector<double> strain(bonds_.i.size(), std::numeric_limits<double>::quiet_NaN());
  const auto& P = particles_;
  std::vector<std::uint8_t> failed(bonds_.i.size(), 0);
  if (const auto* h = std::get_if<std::vector<ElasticBond::State>>(&bonds_.history))
    for (std::size_t b = 0; b < h->size(); ++b) failed[b] = (*h)[b].failed_at >= 0.0;
  for (std::size_t b = 0; b < bonds_.i.size(); ++b) {
    if (bonds_.state[b] != 0 || failed[b] || !(bonds_.rest_length[b] > 0.0)) continue;
    const std::size_t i = static_cast<std::size_t>(bonds_.i[b]), j = static_cast<std::size_t>(bonds_.j[b]);
    const Vec3 d = P.position[j] + packing_.box.shift_vector(bond_image_now(b)) - P.position[i];
    strain[b] = (norm(d) - bonds_.rest_length[b]) / bonds_.rest_length[b];
  }
  return strain;
}

std::size_t Engine::intact_bonds() const {
  std::size_t count = 0;
  for (int st : bonds_.state) count += st == 0;
  return count;
}

template <class BondLaw, bool Measure>
void Engine::bond_forces(int thread, Vec3* force, Vec3* torque, double* stiffness, Totals& local) {
  auto& histories = std::get<std::vector<typename BondLaw::State>>(bonds_.history);
  const std::size_t nb = bonds_.i.size();
  const std::size_t begin = nb * thread / threads_, end = nb * (thread + 1) / threads_;
  const auto& P = particles_;
  const Box& box = packing_.box;
  for (std::size_t b = begin; b < end; ++b) {
    if (bonds_.state[b] != 0) continue;
    const int i = bonds_.i[b], j = bonds_.j[b];
    const Vec3 d = P.position[j] + box.shift_vector(bond_image_now(b)) - P.position[i];
    const double dist = norm(d);
    if (!(dist > 0.0)) continue;  // coincident centres: no direction to act along
    ContactGeometry g = pair_geometry(static_cast<std::size_t>(i), static_cast<std::size_t>(j), d, dist);
    g.rest_length = bonds_.rest_length[b];
    const auto& params = bond_params<BondLaw>(b);
    const BondForce f = BondLaw::evaluate(g, params, histories[b]);
    if (f.failed) {
      ++local.bond_breaks;
      thread_breaks_[thread].push_back(BondBreak{b, time_, box.wrap(P.position[i] + 0.5 * d)});
    }
    if (f.broken) {
      bonds_.state[b] = 1;
      // The pair interacts through the contact law from the next step on. Only this thread
      // touches bond b and its pair.
      if (bonds_.pair[b] >= 0) pair_bonded_[static_cast<std::size_t>(bonds_.pair[b])] = 0;
      continue;
    }
    force[i] -= f.force_on_j;
    force[j] += f.force_on_j;
    torque[i] += f.torque_i;
    torque[j] += f.torque_j;
    const double k = BondLaw::stiffness(params, P.radius[i], P.radius[j], bonds_.rest_length[b]);
    local.max_stiffness_over_mass = std::max(local.max_stiffness_over_mass, k * std::max(P.inverse_mass[i], P.inverse_mass[j]));
    if (stiffness) {
      stiffness[i] += k;
      stiffness[j] += k;
    }
    if constexpr (Measure) {
      local.contact_force_sum += norm(f.force_on_j);
      ++local.contacts;
      local.strain_energy += f.energy;
    }
  }
}

template <class Law, bool Measure, bool SumRule>
void Engine::pair_forces(ContactModel<Law>& model, Totals& totals) {
  const int n = static_cast<int>(particles_.size());
  const int T = threads_;
  const Vec3* __restrict x = particles_.position.data();
  const Vec3* __restrict v = particles_.velocity.data();
  const Vec3* __restrict w = particles_.angular_velocity.data();
  const double* __restrict rad = particles_.radius.data();
  const int* __restrict type = particles_.type.data();
  const int* __restrict first = neighbors_.first_pairs().data();
  const int* __restrict partner = neighbors_.partner().data();
  const std::uint8_t* __restrict image = neighbors_.image().data();
  const int pair_total = first[n];
  const double dt = dt_;
  const int type_count = model.type_count;
  const auto* __restrict params = model.pair_params.data();
  const double* __restrict inverse_mass = particles_.inverse_mass.data();
  auto* __restrict history = model.history.data();
  const std::uint8_t* __restrict bonded = pair_bonded_.data();
  const bool any_bonded = !bonds_.i.empty();
  constexpr bool sum_rule = SumRule;
  if constexpr (sum_rule) thread_stiffness_.resize(static_cast<std::size_t>(T));
  // Several threads and only pair contacts: each thread owns its range of particles and writes
  // their forces directly; a contribution to a particle of a later thread's range goes to a
  // short "ghost" list, added by its owner after the barrier. (With bonds or walls, whose loops
  // are split differently, each thread sums into a whole-size buffer instead; zeroing and
  // summing those buffers costs as much as a sparse packing's contacts.)
  const bool owned = T > 1 && !any_bonded && walls_.empty();
  if (owned) {
    thread_ghosts_.resize(static_cast<std::size_t>(T));
    if constexpr (sum_rule) shared_stiffness_.resize(static_cast<std::size_t>(n));
  }
  std::array<Vec3, 27> offsets;  // local copy: the force stores below cannot alias it
  for (int c = 0; c < 27; ++c) offsets[c] = neighbors_.image_offset(c);

#pragma omp parallel num_threads(T)
  {
    const int t = omp_get_thread_num();
    // Contiguous ranges of particles holding about equal numbers of pairs; each particle's
    // pairs belong to one thread, so its own force is summed in registers.
    auto first_particle = [&](int thread) {
      return static_cast<int>(std::lower_bound(first, first + n, static_cast<int>(static_cast<long>(pair_total) *
                                                                                   thread / T)) -
                              first);
    };
    const int i_begin = first_particle(t);
    const int i_end = t + 1 == T ? n : first_particle(t + 1);
    Vec3* __restrict force;
    Vec3* __restrict torque;
    double* __restrict stiffness = nullptr;
    if (T == 1 || owned) {
      force = particles_.force.data();
      torque = particles_.torque.data();
      // Owned: zero only this thread's range (no other thread writes it before the barrier).
      const int zero_begin = owned ? i_begin : 0, zero_end = owned ? i_end : n;
      std::fill(force + zero_begin, force + zero_end, Vec3{});
      std::fill(torque + zero_begin, torque + zero_end, Vec3{});
      if constexpr (sum_rule) {
        std::vector<double>& buffer = owned ? shared_stiffness_ : thread_stiffness_[t];
        buffer.resize(static_cast<std::size_t>(n));
        stiffness = buffer.data();
        std::fill(stiffness + zero_begin, stiffness + zero_end, 0.0);
      }
      if (owned) thread_ghosts_[t].clear();
    } else {
      thread_force_[t].resize(n);
      thread_torque_[t].resize(n);
      force = thread_force_[t].data();
      torque = thread_torque_[t].data();
      std::fill(force, force + n, Vec3{});
      std::fill(torque, torque + n, Vec3{});
      if constexpr (sum_rule) {
        thread_stiffness_[t].assign(n, 0.0);
        stiffness = thread_stiffness_[t].data();
      }
    }
    std::vector<Ghost>* ghosts = owned ? &thread_ghosts_[t] : nullptr;
    Totals local;
    for (int i = i_begin; i < i_end; ++i) {
      const Vec3 xi = x[i], vi = v[i], wi = w[i];
      const double ri = rad[i];
      const double inverse_mass_i = inverse_mass[i];
      const auto* params_i = params + type[i] * type_count;
      Vec3 force_i{}, torque_i{};
      double stiffness_i = 0.0;
      for (int p = first[i]; p < first[i + 1]; ++p) {
        const int j = partner[p];
        const Vec3 d = x[j] + offsets[image[p]] - xi;
        const double dist2 = norm2(d);
        const double rsum = ri + rad[j];
        if (dist2 >= rsum * rsum || (any_bonded && bonded[p])) {
          // Not touching (its history ends), or bonded (the bond law acts instead).
          history[p] = typename Law::History{};
          continue;
        }
        const double dist = std::sqrt(dist2);
        // pair_geometry() inlined with particle i's data held in registers (hot loop).
        ContactGeometry g;
        g.normal = d * (1.0 / dist);
        g.overlap = rsum - dist;
        g.branch_i = ri - 0.5 * g.overlap;
        g.branch_j = rad[j] - 0.5 * g.overlap;
        g.relative_velocity = v[j] - vi - cross(g.branch_j * w[j] + g.branch_i * wi, g.normal);
        g.mean_spin = 0.5 * (wi + w[j]);
        g.dt = dt;
        // Unused by laws that do not need them (the compiler drops the loads).
        g.radius_i = ri;
        g.radius_j = rad[j];
        // Two fixed particles: 0, not infinity (a select, no branch), so no NaN reaches them.
        const double inverse_sum = inverse_mass_i + inverse_mass[j];
        g.effective_mass = inverse_sum > 0.0 ? 1.0 / inverse_sum : 0.0;
        g.spin_i = wi;
        g.spin_j = w[j];
        const auto& pair_params = params_i[type[j]];
        const PairForce f = Law::evaluate(g, pair_params, history[p]);
        local.max_stiffness_over_mass =
            std::max(local.max_stiffness_over_mass, f.stiffness * std::max(inverse_mass_i, inverse_mass[j]));
        force_i -= f.force_on_j;
        torque_i += f.torque_i;
        if constexpr (sum_rule) stiffness_i += f.stiffness;
        if (ghosts && j >= i_end) {
          ghosts->push_back(Ghost{j, f.force_on_j, f.torque_j, f.stiffness});
        } else {
          force[j] += f.force_on_j;
          torque[j] += f.torque_j;
          if constexpr (sum_rule) stiffness[j] += f.stiffness;
        }
        if constexpr (Measure) {
          ++local.contacts;
          local.contact_force_sum += norm(f.force_on_j);
          local.strain_energy += f.energy;
          local.max_overlap_ratio = std::max(local.max_overlap_ratio, g.overlap / rsum);
        }
      }
      force[i] += force_i;
      torque[i] += torque_i;
      if constexpr (sum_rule) stiffness[i] += stiffness_i;
    }
    if (any_bonded) {
      if (std::holds_alternative<std::vector<ContactBond::State>>(bonds_.history))
        bond_forces<ContactBond, Measure>(t, force, torque, stiffness, local);
      else
        bond_forces<ElasticBond, Measure>(t, force, torque, stiffness, local);
    }
    if (!walls_.empty()) wall_forces<Law, Measure>(model, t, force, torque, stiffness, local);
    thread_totals_[t] = local;
#pragma omp barrier
    if (owned) {
      // Contributions of earlier threads to this thread's particles, in thread order:
      // deterministic for a fixed thread count.
      for (int s = 0; s < t; ++s)
        for (const Ghost& g : thread_ghosts_[s]) {
          if (g.particle < i_begin || g.particle >= i_end) continue;
          force[g.particle] += g.force;
          torque[g.particle] += g.torque;
          if constexpr (sum_rule) stiffness[g.particle] += g.stiffness;
        }
    } else if (T > 1) {
      // Sum the thread buffers in thread order: deterministic for a fixed thread count.
#pragma omp for schedule(static)
      for (int k = 0; k < n; ++k) {
        Vec3 f{}, m{};
        for (int s = 0; s < T; ++s) {
          f += thread_force_[s][k];
          m += thread_torque_[s][k];
        }
        particles_.force[k] = f;
        particles_.torque[k] = m;
      }
    }
    if constexpr (sum_rule) {
      // The stiffest particle: sum of its contact stiffnesses over its mass (fixed particles
      // have zero inverse mass and drop out). Max is order-independent: deterministic.
      double largest = 0.0;
      if (T == 1 || owned) {
        for (int k = i_begin; k < i_end; ++k) largest = std::max(largest, stiffness[k] * inverse_mass[k]);
      } else {
#pragma omp for schedule(static)
        for (int k = 0; k < n; ++k) {
          double sum = 0.0;
          for (int s = 0; s < T; ++s) sum += thread_stiffness_[s][k];
          largest = std::max(largest, sum * inverse_mass[k]);
        }
      }
      thread_totals_[t].max_stiffness_over_mass = largest;
    }
  }
  for (int t = 0; t < T; ++t) {
    totals.max_stiffness_over_mass = std::max(totals.max_stiffness_over_mass, thread_totals_[t].max_stiffness_over_mass);
    totals.bond_breaks += thread_totals_[t].bond_breaks;
  }
  for (std::size_t m = 0; m < walls_.size(); ++m) {
    Vec3 sum{};
    for (int t = 0; t < T; ++t) sum += thread_wall_force_[t][m];
    wall_force_[m] = sum;
  }
  broken_bonds_ += totals.bond_breaks;
  if (totals.bond_breaks > 0)
    for (int t = 0; t < T; ++t) {
      breaks_.insert(breaks_.end(), thread_breaks_[t].begin(), thread_breaks_[t].end());
      thread_breaks_[t].clear();
    }
  if constexpr (Measure) {
    for (int t = 0; t < T; ++t) {
      totals.contacts += thread_totals_[t].contacts;
      totals.contact_force_sum += thread_totals_[t].contact_force_sum;
      totals.strain_energy += thread_totals_[t].strain_energy;
      totals.max_overlap_ratio = std::max(totals.max_overlap_ratio, thread_totals_[t].max_overlap_ratio);
    }
  }
}

template <bool Measure>
void Engine::integrate(Totals& totals) {
  const int n = static_cast<int>(particles_.size());
  const double dt = dt_;
  auto& P = particles_;
  double kinetic = 0.0, unbalanced = 0.0;
  long free_count = 0;
#pragma omp parallel for num_threads(threads_) schedule(static) reduction(+ : kinetic, unbalanced, free_count)
  for (int i = 0; i < n; ++i) {
    // Fixed particles have zero inverse mass and inertia: they keep zero velocity without a
    // branch, so the loop vectorizes.
    const double alpha = damping_[i];
    const Vec3 f = apply_local_damping(P.force[i], P.velocity[i], alpha);
    const Vec3 m = apply_local_damping(P.torque[i], P.angular_velocity[i], alpha);
    const Vec3 dv = (P.inverse_mass[i] * dt) * f;
    const Vec3 dw = (P.inverse_inertia[i] * dt) * m;
    if constexpr (Measure) {
      if (!P.fixed[i]) {
        const Vec3 v_sync = P.velocity[i] + 0.5 * dv;
        const Vec3 w_sync = P.angular_velocity[i] + 0.5 * dw;
        kinetic += 0.5 * (P.mass[i] * norm2(v_sync) + P.inertia[i] * norm2(w_sync));
        unbalanced += norm(P.force[i]);
        ++free_count;
      }
    }
    P.velocity[i] += dv;
    P.angular_velocity[i] += dw;
    P.position[i] += dt * P.velocity[i];
  }
  if constexpr (Measure) {
    totals.kinetic_energy = kinetic;
    totals.unbalanced_force_sum = unbalanced;
    totals.free_particles = static_cast<std::size_t>(free_count);
  }
}

template <bool Measure>
Engine::Totals Engine::step_impl() {
  if (neighbors_.needs_rebuild(particles_.position, particles_.radius)) refresh_neighbors();
  Totals totals;
  std::visit(
      [&](auto& model) {
        using Law = std::decay_t<decltype(model.law)>;
        if (config_.time_step <= 0.0 && config_.time_step_rule == TimeStepRule::stiffness_sum)
          pair_forces<Law, Measure, true>(model, totals);
        else
          pair_forces<Law, Measure, false>(model, totals);
      },
      model_);
  if (config_.time_step <= 0.0 && config_.time_step_rule != TimeStepRule::global) {
    dt_ = totals.max_stiffness_over_mass > 0.0
              ? std::min(time_step_cap_, config_.time_step_safety / std::sqrt(totals.max_stiffness_over_mass))
              : time_step_cap_;
  }
  integrate<Measure>(totals);
  for (auto& wall : walls_) wall.point += dt_ * wall.velocity;
  ++step_;
  time_ += dt_;
  return totals;
}

void Engine::run(long steps) {
  for (long s = 0; s < steps; ++s) step_impl<false>();
}

Diagnostics Engine::step_measured() {
  Diagnostics d;
  d.step = step_;
  d.time = time_;
  const Totals t = step_impl<true>();
  d.kinetic_energy = t.kinetic_energy;
  d.strain_energy = t.strain_energy;
  d.contacts = t.contacts;
  d.max_overlap_ratio = t.max_overlap_ratio;
  const std::size_t n = particles_.size();
  d.mean_coordination = n ? 2.0 * static_cast<double>(t.contacts) / static_cast<double>(n) : 0.0;
  d.intact_bonds = intact_bonds();
  d.broken_bonds = broken_bonds_;
  if (t.contacts > 0 && t.free_particles > 0 && t.contact_force_sum > 0.0)
    d.unbalanced_force_ratio = (t.unbalanced_force_sum / static_cast<double>(t.free_particles)) /
                               (t.contact_force_sum / static_cast<double>(t.contacts));
  return d;
}

namespace {
constexpr std::uint64_t checkpoint_magic = 0x314B43454D454450ULL;  // "PDEMECK1"
}

void Engine::save_state(std::ostream& out) const {
  binary::write(out, checkpoint_magic);
  binary::write(out, static_cast<std::uint64_t>(particles_.size()));
  binary::write(out, static_cast<std::uint64_t>(model_.index()));
  binary::write(out, step_);
  binary::write(out, time_);
  binary::write(out, dt_);
  const auto& P = particles_;
  binary::write_vector(out, P.position);
  binary::write_vector(out, P.velocity);
  binary::write_vector(out, P.angular_velocity);
  binary::write_vector(out, P.force);
  binary::write_vector(out, P.torque);
  binary::write_vector(out, P.radius);
  binary::write_vector(out, P.type);
  binary::write_vector(out, P.fixed);
  binary::write_vector(out, density_);
  binary::write_vector(out, damping_);
  binary::write_vector(out, original_index_);
  binary::write_vector(out, wraps_);
  binary::write_vector(out, bonds_.state);
  std::visit([&](const auto& h) { binary::write_vector(out, h); }, bonds_.history);
  binary::write(out, static_cast<std::uint64_t>(broken_bonds_));
  binary::write_vector(out, walls_);
  binary::write_vector(out, wall_history_);
  binary::write_vector(out, wall_force_);
  neighbors_.save(out);
  std::visit([&](const auto& model) { binary::write_vector(out, model.history); }, model_);
  binary::write_vector(out, breaks_);
}

void Engine::load_state(std::istream& in) {
  std::uint64_t magic = 0, n = 0, law = 0;
  binary::read(in, magic, "header");
  if (magic != checkpoint_magic) fail_input("checkpoint: not a packlab engine state (bad header)");
  binary::read(in, n, "particle count");
  binary::read(in, law, "contact law");
  if (n != particles_.size())
    fail_input(fmt::format("checkpoint holds {} particles, the engine {}", n, particles_.size()));
  if (law != model_.index()) fail_input("checkpoint was written with another contact law");
  binary::read(in, step_, "step");
  binary::read(in, time_, "time");
  binary::read(in, dt_, "time step");
  auto& P = particles_;
  binary::read_vector(in, P.position, "positions");
  binary::read_vector(in, P.velocity, "velocities");
  binary::read_vector(in, P.angular_velocity, "angular velocities");
  binary::read_vector(in, P.force, "forces");
  binary::read_vector(in, P.torque, "torques");
  binary::read_vector(in, P.radius, "radii");
  binary::read_vector(in, P.type, "types");
  binary::read_vector(in, P.fixed, "fixed flags");
  binary::read_vector(in, density_, "densities");
  binary::read_vector(in, damping_, "damping");
  binary::read_vector(in, original_index_, "particle order");
  binary::read_vector(in, wraps_, "periodic images");
  std::vector<int> bond_state;
  binary::read_vector(in, bond_state, "bond states");
  std::size_t history_size = 0;
  std::visit(
      [&](auto& h) {
        binary::read_vector(in, h, "bond histories");
        history_size = h.size();
      },
      bonds_.history);
  std::uint64_t broken = 0;
  binary::read(in, broken, "broken bond count");
  if (wraps_.size() != n || bond_state.size() != bonds_.i.size() || history_size != bonds_.i.size())
    fail_input("checkpoint does not match this packing's particles and bonds");
  bonds_.state = std::move(bond_state);
  broken_bonds_ = broken;
  binary::read_vector(in, walls_, "walls");
  binary::read_vector(in, wall_history_, "wall contact histories");
  binary::read_vector(in, wall_force_, "wall forces");
  if (wall_history_.size() != n * walls_.size() || wall_force_.size() != walls_.size())
    fail_input("checkpoint is damaged: wall data do not match");
  for (auto* v : {&P.position, &P.velocity, &P.angular_velocity, &P.force, &P.torque})
    if (v->size() != n) fail_input("checkpoint is damaged: array sizes differ");
  if (P.radius.size() != n || P.type.size() != n || P.fixed.size() != n || density_.size() != n ||
      damping_.size() != n || original_index_.size() != n)
    fail_input("checkpoint is damaged: array sizes differ");
  for (std::size_t k = 0; k < n; ++k) update_mass(k);
  masses_changed();
  neighbors_.load(in);
  std::visit([&](auto& model) { binary::read_vector(in, model.history, "contact histories"); }, model_);
  if (neighbors_.particle_count() != n || std::visit([&](auto& m) { return m.history.size(); }, model_) !=
                                              neighbors_.pair_count())
    fail_input("checkpoint is damaged: contact histories do not match the neighbour list");
  binary::read_vector(in, breaks_, "bond breaks");
  mark_bonded_pairs();
}

Packing Engine::packing() const {
  Packing out = packing_;
  const std::size_t n = particles_.size();
  out.velocity.resize(n);
  out.angular_velocity.resize(n);
  // Total wraps since the input of each particle as written (internal wraps + this wrap).
  std::vector<std::array<int, 3>> total_wraps(wraps_);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = static_cast<std::size_t>(original_index_[k]);
    out.position[i] = out.box.wrap(particles_.position[k], &total_wraps[k]);
    out.radius[i] = particles_.radius[k];
    out.velocity[i] = particles_.velocity[k];
    out.angular_velocity[i] = particles_.angular_velocity[k];
  }
  for (std::size_t b = 0; b < bonds_.i.size(); ++b) {
    const auto& wi = total_wraps[static_cast<std::size_t>(bonds_.i[b])];
    const auto& wj = total_wraps[static_cast<std::size_t>(bonds_.j[b])];
    for (int a = 0; a < 3; ++a) out.bonds.image[b][a] = bonds_.image[b][a] + wj[a] - wi[a];
    out.bonds.state[b] = bonds_.state[b];
  }
  return out;
}

}  // namespace packlab::dem
