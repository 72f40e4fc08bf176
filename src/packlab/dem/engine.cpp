// Engine set-up: validation of the packing and the parameters, particle arrays in the engine's
// order, the contact and bond models from the law registries, masses; the packing and bond
// state read back out. The step loop is in step.cpp, the time-step rules in time_step.cpp.
#include "packlab/dem/engine.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

#include "packlab/core/error.hpp"
#include "packlab/core/memory.hpp"

namespace packlab::dem {

std::vector<std::string> contact_law_names() { return ContactLaws::names(); }
std::vector<std::string> bond_law_names() { return BondLaws::names(); }

std::string bond_law_name(const BondMaterials& materials) {
  std::string name;
  BondLaws::for_each([&](auto law) {
    using Law = typename decltype(law)::type;
    if (std::holds_alternative<BondMaterialList<Law>>(materials)) name = Law::name;
  });
  return name;
}

namespace {

template <class Law>
ContactModel<Law> make_model(const std::vector<Material>& types, int type_count, StiffnessRule rule) {
  validate(types, Law::properties);
  ContactModel<Law> model;
  model.type_count = type_count;
  model.pair_params.resize(static_cast<std::size_t>(type_count) * type_count);
  auto of = [&](int t) -> const Material& { return types.size() == 1 ? types[0] : types[t]; };
  for (int a = 0; a < type_count; ++a)
    for (int b = 0; b < type_count; ++b) model.pair_params[a * type_count + b] = Law::mix(of(a), of(b), rule);
  return model;
}

ContactModels make_contact_model(const std::string& name, const std::vector<Material>& types, int type_count,
                                 StiffnessRule rule) {
  ContactModels model;
  if (!ContactLaws::with_law(
          name, [&](auto law) { model = make_model<typename decltype(law)::type>(types, type_count, rule); }))
    fail_input(fmt::format("contact_law = {}: must be one of: {}", name, fmt::join(contact_law_names(), ", ")));
  return model;
}

// The bond model of the configured law, its parameters validated, a history per bond.
template <class Law>
BondModel<Law> make_bond_model(const BondMaterialList<Law>& list, const Bonds& bonds) {
  bool any_intact = false;
  for (int s : bonds.state) any_intact = any_intact || s == 0;
  if (any_intact && list.empty())
    fail_input(fmt::format("the packing has bonds but no parameters were given for the '{}' bond law", Law::name));
  for (std::size_t m = 0; m < list.size(); ++m)
    validate_parameters(list[m], Law::parameters, fmt::format("{} bond material {} ", Law::name, m));
  const std::size_t count = list.size();
  for (std::size_t b = 0; any_intact && b < bonds.size(); ++b) {
    if (count > 1 && (bonds.material[b] < 0 || static_cast<std::size_t>(bonds.material[b]) >= count))
      fail_input(fmt::format("bond {} has material {}: parameters were given for materials 0..{}", b, bonds.material[b],
                             count - 1));
    if (Law::uses_rest_length && !(bonds.rest_length[b] > 0.0))
      fail_input(
          fmt::format("bond {} has rest length {:g}: must be > 0 m for {} bonds", b, bonds.rest_length[b], Law::name));
  }
  BondModel<Law> model;
  model.materials = list;
  model.history.resize(bonds.size());
  return model;
}

BondModels make_bond_model(const BondMaterials& materials, const Bonds& bonds) {
  BondModels model;
  BondLaws::for_each([&](auto law) {
    using Law = typename decltype(law)::type;
    if (const auto* list = std::get_if<BondMaterialList<Law>>(&materials)) model = make_bond_model<Law>(*list, bonds);
  });
  return model;
}

}  // namespace

namespace {

// Two particles at one point have no contact normal: their force is NaN and spreads through the
// packing within a few steps (a shear test then reported a modulus 12 % low, a compression
// test failed at the end writing NaN). Exact duplicates are what readers and scripts produce.
void require_distinct_positions(const Packing& packing) {
  std::vector<std::size_t> order(packing.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto key = [&](std::size_t i) {
    const Vec3& p = packing.position[i];
    return std::make_tuple(p.x, p.y, p.z);
  };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  for (std::size_t k = 1; k < order.size(); ++k)
    if (key(order[k]) == key(order[k - 1])) {
      const Vec3& p = packing.position[order[k]];
      fail_input(
          fmt::format("particles {} and {} are at the same position ({:g}, {:g}, {:g}): a contact between "
                      "them has no direction; remove one of them",
                      std::min(order[k], order[k - 1]), std::max(order[k], order[k - 1]), p.x, p.y, p.z));
    }
}

}  // namespace

Engine::Engine(const Packing& packing, const EngineConfig& config) : packing_(packing), config_(config) {
  packing_.validate();
  require_distinct_positions(packing_);
  validate(config_.types);
  require(config_.time_step >= 0.0 && std::isfinite(config_.time_step), "time_step", config_.time_step,
          ">= 0 s (0 = automatic)");
  require(config_.time_step_safety > 0.0 && config_.time_step_safety <= 1.0, "time_step_safety",
          config_.time_step_safety, "in (0, 1]");
  require(config_.skin_ratio > 0.0 && config_.skin_ratio <= 10.0, "skin_ratio", config_.skin_ratio, "in (0, 10]");
  require(config_.near_margin_ratio >= 0.0 && config_.near_margin_ratio <= 1.0, "near_margin_ratio",
          config_.near_margin_ratio, "in [0, 1] (0 = no near list)");
  require(config_.max_time_step >= 0.0 && std::isfinite(config_.max_time_step), "max_time_step", config_.max_time_step,
          ">= 0 s (0 = automatic)");
  // An OpenMP team of 10^5 threads crashes the runtime; no machine this runs on has more than 1024 cores.
  require(config_.threads >= 0 && config_.threads <= 1024, "threads", config_.threads, "in [0, 1024] (0 = all cores)");

  const std::size_t n = packing_.size();
  int type_count = 1;
  for (int t : packing_.type) type_count = std::max(type_count, t + 1);
  if (config_.types.size() > 1 && static_cast<int>(config_.types.size()) < type_count)
    fail_input(fmt::format("the packing has particle type {} but parameters were given for {} types", type_count - 1,
                           config_.types.size()));

  double r_max = 0.0;
  for (double r : packing_.radius) r_max = std::max(r_max, r);
  original_index_ = curve_order(packing_.position, r_max);
  particles_.resize(n);
  // Per type, not per particle (issue #14: bytes per particle).
  type_damping_.resize(static_cast<std::size_t>(type_count));
  for (int t = 0; t < type_count; ++t) type_damping_[static_cast<std::size_t>(t)] = params_of_type(t).damping;
  if (!packing_.density.empty()) density_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = static_cast<std::size_t>(original_index_[k]);
    const double r = packing_.radius[i];
    particles_.position[k] = packing_.position[i];
    particles_.velocity[k] = packing_.velocity.empty() ? Vec3{} : packing_.velocity[i];
    particles_.angular_velocity[k] = packing_.angular_velocity.empty() ? Vec3{} : packing_.angular_velocity[i];
    particles_.radius[k] = r;
    particles_.type[k] = packing_.type[i];
    particles_.fixed[k] = packing_.fixed.empty() ? 0 : packing_.fixed[i];
    if (!density_.empty()) density_[k] = packing_.density[i];
    update_mass(k);
    if (particles_.fixed[k]) particles_.velocity[k] = particles_.angular_velocity[k] = Vec3{};
  }

  model_ = make_contact_model(config_.contact_law, config_.types, type_count, config_.stiffness_rule);
  bond_model_ = make_bond_model(config_.bond_materials, packing_.bonds);
  // How far beyond touching the contact law acts: listed pairs must cover it.
  double reach = 0.0;
  std::visit(
      [&](const auto& model) {
        for (const auto& p : model.pair_params) reach = std::max(reach, model.law.reach(p));
      },
      model_);
  require(std::isfinite(reach) && reach <= 10.0 * r_max, "contact law reach", reach, "<= 10 times the largest radius");
  // Torque-free: the law says so for every pair of types (walls take the pair params of the
  // particle's type with itself), and no bond may act.
  std::visit(
      [&](const auto& model) {
        using Law = std::decay_t<decltype(model.law)>;
        if constexpr (requires(const typename Law::Params& p) { Law::torque_free(p); }) {
          spin_free_ = packing_.bonds.size() == 0;
          for (const auto& p : model.pair_params) spin_free_ = spin_free_ && Law::torque_free(p);
        }
        pair_histories_ = !(has_central_form<Law> && spin_free_);
      },
      model_);

  // Bonds, mapped to the engine's particle order and stored by their owner (the smaller
  // particle index), then by their index in the input: the step walks them owner by owner, so
  // their arrays and histories are read and written in order, and each thread's bonds are one
  // contiguous stretch (issue #14: one thread 12 % faster on the bonded compression benchmark
  // than with the input's order, docs/engine.md). bond_input_index_ maps back for the API.
  wraps_.assign(n, {0, 0, 0});
  {
    std::vector<int> internal(n);
    for (std::size_t k = 0; k < n; ++k) internal[static_cast<std::size_t>(original_index_[k])] = static_cast<int>(k);
    const Bonds& in = packing_.bonds;
    constexpr int image_limit = std::numeric_limits<std::int16_t>::max();
    constexpr int material_limit = std::numeric_limits<std::uint16_t>::max();
    // Checked in the input's order, so that the first bad bond is the one named.
    for (std::size_t b = 0; b < in.size(); ++b) {
      const auto& s = in.image[b];
      for (const int a : s)
        if (a < -image_limit || a > image_limit)
          fail_input(fmt::format("bond {} has image {} {} {}: each component must be in [{}, {}]", b, s[0], s[1], s[2],
                                 -image_limit, image_limit));
      if (in.material[b] < 0 || in.material[b] > material_limit)
        fail_input(fmt::format("bond {} has material {}: must be in [0, {}]", b, in.material[b], material_limit));
    }
    auto owner = [&](std::size_t b) {
      return static_cast<std::size_t>(
          std::min(internal[static_cast<std::size_t>(in.i[b])], internal[static_cast<std::size_t>(in.j[b])]));
    };
    // Both empty without bonds.
    bond_input_index_.resize(in.size());
    if (!in.i.empty()) {
      bond_first_.assign(n + 1, 0);
      for (std::size_t b = 0; b < in.size(); ++b) ++bond_first_[owner(b) + 1];
      for (std::size_t k = 0; k < n; ++k) bond_first_[k + 1] += bond_first_[k];
      std::vector<int> next(bond_first_.begin(), bond_first_.end() - 1);
      for (std::size_t b = 0; b < in.size(); ++b)
        bond_input_index_[static_cast<std::size_t>(next[owner(b)]++)] = static_cast<int>(b);
    }
    // Exactly as many as there are (grown one by one, the lists would keep up to twice that).
    bonds_.i.reserve(in.size());
    bonds_.j.reserve(in.size());
    bonds_.image.reserve(in.size());
    bonds_.material.reserve(in.size());
    bonds_.rest_length.reserve(in.size());
    bonds_.state.reserve(in.size());
    for (const int input_bond : bond_input_index_) {
      const auto b = static_cast<std::size_t>(input_bond);
      const auto& s = in.image[b];
      bonds_.i.push_back(internal[static_cast<std::size_t>(in.i[b])]);
      bonds_.j.push_back(internal[static_cast<std::size_t>(in.j[b])]);
      bonds_.image.push_back(
          {static_cast<std::int16_t>(s[0]), static_cast<std::int16_t>(s[1]), static_cast<std::int16_t>(s[2])});
      bonds_.material.push_back(static_cast<std::uint16_t>(in.material[b]));
      bonds_.rest_length.push_back(in.rest_length[b]);
      bonds_.state.push_back(in.state[b] == 0 ? 0 : 1);
      if (in.state[b] != 0) ++broken_bonds_;
    }
  }
  threads_ = config_.threads > 0 ? config_.threads : omp_get_max_threads();
  require(config_.thread_probe_every > 0.0 && std::isfinite(config_.thread_probe_every), "thread_probe_every",
          config_.thread_probe_every, "> 0 s");
  require(config_.thread_probe_seconds > 0.0 && config_.thread_probe_seconds <= 60.0, "thread_probe_seconds",
          config_.thread_probe_seconds, "in (0, 60] s");
  tuning_.configured = threads_;
  // Adapting, the engine starts at one thread and goes up when two probes in a row find more
  // threads faster (tune_threads): on a loaded machine more threads can be several times slower
  // than one, and a probe sometimes misjudges (docs/engine.md, "Parallelism").
  if (config_.adapt_threads) threads_ = 1;
  tuning_.best = threads_;
  // The first probe after a few hundred steps: the first ones touch memory for the first time.
  tuning_.steps_to_probe = 300;
  // Everything per particle and per bond now lives in particles_, density_ and bonds_:
  // packing() rebuilds the input's arrays from them.
  input_has_density_ = !packing_.density.empty();
  input_has_fixed_ = !packing_.fixed.empty();
  release_memory(packing_.position);
  release_memory(packing_.radius);
  release_memory(packing_.type);
  release_memory(packing_.velocity);
  release_memory(packing_.angular_velocity);
  release_memory(packing_.density);
  release_memory(packing_.fixed);
  packing_.bonds = Bonds{};

  neighbors_.set_skin(config_.skin_ratio * r_max);
  near_base_margin_ = near_margin_ = config_.near_margin_ratio * neighbors_.skin();
  neighbors_.set_reach(reach);
  neighbors_.set_history_map(pair_histories_);
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

const Material& Engine::params_of_type(int type) const {
  return config_.types.size() == 1 ? config_.types[0] : config_.types[type];
}

void Engine::update_mass(std::size_t k) {
  const double r = particles_.radius[k];
  const double density = density_.empty() ? params_of_type(particles_.type[k]).density : density_[k];
  particles_.mass[k] = density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  particles_.inverse_mass[k] = particles_.fixed[k] ? 0.0 : 1.0 / particles_.mass[k];
  particles_.inverse_inertia[k] = particles_.fixed[k] ? 0.0 : 1.0 / sphere_inertia(particles_.mass[k], r);
}

void Engine::set_radius_of_type(int type, double radius) {
  require(radius > 0.0 && std::isfinite(radius), "radius", radius, "> 0 m");
  for (std::size_t k = 0; k < particles_.size(); ++k)
    if (particles_.type[k] == type) {
      particles_.radius[k] = radius;
      update_mass(k);
    }
  near_stale_ = true;  // pairs may reach further (dem/near_pairs.cpp)
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
  near_stale_ = true;  // pairs may reach further (dem/near_pairs.cpp)
  masses_changed();
}

void Engine::masses_changed() {
  time_step_cap_ = config_.max_time_step > 0.0 ? config_.max_time_step : heaviest_particle_time_step();
}

std::vector<double> Engine::bond_strains() const {
  std::vector<double> strain(bonds_.i.size(), std::numeric_limits<double>::quiet_NaN());
  std::visit(
      [&](const auto& model) {
        for (std::size_t b = 0; b < bonds_.i.size(); ++b) {
          if (bonds_.state[b] != 0 || model.law.failed(model.history[b]) || !(bonds_.rest_length[b] > 0.0)) continue;
          strain[static_cast<std::size_t>(bond_input_index_[b])] =
              (norm(bond_vector(b)) - bonds_.rest_length[b]) / bonds_.rest_length[b];
        }
      },
      bond_model_);
  return strain;
}

std::size_t Engine::intact_bonds() const {
  std::size_t count = 0;
  for (const std::uint8_t st : bonds_.state) count += st == 0;
  return count;
}

EngineMemory Engine::memory() const {
  EngineMemory m;
  const ParticleStore& P = particles_;
  m.particles = heap_bytes(P.position) + heap_bytes(P.velocity) + heap_bytes(P.angular_velocity) + heap_bytes(P.force) +
                heap_bytes(P.torque) + heap_bytes(P.radius) + heap_bytes(P.mass) + heap_bytes(P.inverse_mass) +
                heap_bytes(P.inverse_inertia) + heap_bytes(P.type) + heap_bytes(P.fixed) + heap_bytes(type_damping_) +
                heap_bytes(original_index_) + heap_bytes(density_) + heap_bytes(wraps_) + heap_bytes(stiffness_sum_) +
                heap_bytes(measure_energy_) + heap_bytes(measure_force_) + heap_bytes(chunk_sums_) +
                heap_bytes(bond_first_);
  const NeighborList::Memory list = neighbors_.memory();
  m.neighbor_list = list.per_particle_arrays;
  m.listed_pairs = list.per_pair_arrays + heap_bytes(pair_bonded_);
  std::visit([&](const auto& model) { m.contact_history = heap_bytes(model.history) + heap_bytes(model.wall_history); },
             model_);
  m.bonds = heap_bytes(bonds_.i) + heap_bytes(bonds_.j) + heap_bytes(bonds_.image) + heap_bytes(bonds_.material) +
            heap_bytes(bonds_.rest_length) + heap_bytes(bonds_.state) + heap_bytes(bond_input_index_) +
            heap_bytes(breaks_);
  std::visit([&](const auto& model) { m.bonds += heap_bytes(model.history); }, bond_model_);
  for (const ThreadWork& w : work_) {
    m.bonds += heap_bytes(w.failed_bonds) + heap_bytes(w.failed_positions);
    m.threads += heap_bytes(w.crossing_pairs) + heap_bytes(w.crossing_pair_owners) +
                 heap_bytes(w.crossing_pair_results) + heap_bytes(w.crossing_pair_acts) + heap_bytes(w.crossing_bonds) +
                 heap_bytes(w.crossing_bond_results);
    m.listed_pairs += heap_bytes(w.near_pairs) + heap_bytes(w.near_owners);  // the near list
  }
  return m;
}

Packing Engine::packing() const {
  Packing out;
  out.box = packing_.box;
  out.fields = packing_.fields;
  const std::size_t n = particles_.size();
  out.position.resize(n);
  out.radius.resize(n);
  out.type.resize(n);
  out.velocity.resize(n);
  out.angular_velocity.resize(n);
  if (input_has_density_) out.density.resize(n);
  if (input_has_fixed_) out.fixed.resize(n);
  // Total wraps since the input of each particle as written (internal wraps + this wrap).
  std::vector<std::array<int, 3>> total_wraps(wraps_);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = static_cast<std::size_t>(original_index_[k]);
    out.position[i] = out.box.wrap(particles_.position[k], &total_wraps[k]);
    out.radius[i] = particles_.radius[k];
    out.type[i] = particles_.type[k];
    out.velocity[i] = particles_.velocity[k];
    out.angular_velocity[i] = particles_.angular_velocity[k];
    if (input_has_density_) out.density[i] = density_[k];
    if (input_has_fixed_) out.fixed[i] = particles_.fixed[k];
  }
  const std::size_t bond_count = bonds_.i.size();
  out.bonds.i.resize(bond_count);
  out.bonds.j.resize(bond_count);
  out.bonds.image.resize(bond_count);
  out.bonds.material.resize(bond_count);
  out.bonds.rest_length.resize(bond_count);
  out.bonds.state.resize(bond_count);
  for (std::size_t b = 0; b < bond_count; ++b) {
    const auto input = static_cast<std::size_t>(bond_input_index_[b]);
    const auto bi = static_cast<std::size_t>(bonds_.i[b]), bj = static_cast<std::size_t>(bonds_.j[b]);
    out.bonds.i[input] = original_index_[bi];
    out.bonds.j[input] = original_index_[bj];
    const auto& wi = total_wraps[bi];
    const auto& wj = total_wraps[bj];
    for (int a = 0; a < 3; ++a) out.bonds.image[input][a] = bonds_.image[b][a] + wj[a] - wi[a];
    out.bonds.material[input] = bonds_.material[b];
    out.bonds.rest_length[input] = bonds_.rest_length[b];
    out.bonds.state[input] = bonds_.state[b];
  }
  return out;
}

}  // namespace packlab::dem
