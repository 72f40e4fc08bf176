// The engine's whole dynamic state in a binary checkpoint (Engine::save_state / load_state).
#include <fmt/format.h>

#include <type_traits>

#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/memory.hpp"
#include "packlab/dem/engine.hpp"

namespace packlab::dem {

namespace {
// "PDEMECK5": the particle sort's reference distance (resort_particles). (4: no per-particle
// damping, densities only when the input had them; 3: one-byte bond states, scalar bond
// torsion.)
constexpr std::uint64_t checkpoint_magic = 0x354B43454D454450ULL;

}  // namespace

void Engine::save_state(std::ostream& out) const {
  binary::write(out, checkpoint_magic);
  binary::write(out, static_cast<std::uint64_t>(particles_.size()));
  // The laws by name (a tag that survives reordering the registries).
  binary::write_string(out, config_.contact_law);
  binary::write_string(out, bond_law_name(config_.bond_materials));
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
  binary::write_vector(out, original_index_);
  binary::write_vector(out, wraps_);
  // Bonds in the packing's order (the engine keeps them by owner): a checkpoint's bonds do not
  // depend on how the engine stores them.
  const auto in_input_order = [&](const auto& v) {
    std::decay_t<decltype(v)> out_order(v.size());
    for (std::size_t b = 0; b < v.size(); ++b) out_order[static_cast<std::size_t>(bond_input_index_[b])] = v[b];
    return out_order;
  };
  binary::write_vector(out, in_input_order(bonds_.state));
  std::visit([&](const auto& bonds) { binary::write_vector(out, in_input_order(bonds.history)); }, bond_model_);
  binary::write(out, static_cast<std::uint64_t>(broken_bonds_));
  binary::write_vector(out, walls_);
  std::visit([&](const auto& model) { binary::write_vector(out, model.wall_history); }, model_);
  binary::write_vector(out, wall_force_);
  neighbors_.save(out);
  std::visit([&](const auto& model) { binary::write_vector(out, model.history); }, model_);
  binary::write_vector(out, breaks_);
  binary::write(out, sorted_index_distance_);
  binary::write(out, resorts_);
}

void Engine::load_state(std::istream& in) {
  std::uint64_t magic = 0, n = 0;
  binary::read(in, magic, "header");
  binary::require_header(magic, checkpoint_magic, "checkpoint: not a packlab engine state");
  binary::read(in, n, "particle count");
  if (n != particles_.size())
    fail_input(fmt::format("checkpoint holds {} particles, the engine {}", n, particles_.size()));
  std::string contact_law, bond_law;
  binary::read_string(in, contact_law, "contact law");
  binary::read_string(in, bond_law, "bond law");
  if (contact_law != config_.contact_law)
    fail_input(fmt::format("checkpoint was written with contact law '{}', the engine uses '{}'", contact_law,
                           config_.contact_law));
  if (bond_law != bond_law_name(config_.bond_materials))
    fail_input(fmt::format("checkpoint was written with bond law '{}', the engine uses '{}'", bond_law,
                           bond_law_name(config_.bond_materials)));
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
  const std::vector<int> built_order = original_index_;
  binary::read_vector(in, original_index_, "particle order");
  // Bonds are kept in the order the engine was built with (only engines without bonds sort
  // their particles again: resort_particles).
  if (!bonds_.i.empty() && original_index_ != built_order)
    fail_input("checkpoint is damaged: the particle order does not match the bonded model's");
  binary::read_vector(in, wraps_, "periodic images");
  std::vector<std::uint8_t> bond_state;
  binary::read_vector(in, bond_state, "bond states");
  // Reads the history vector `member` of the law model held by `models`; returns its size.
  const auto read_histories = [&](auto& models, auto member, const char* what) {
    return std::visit(
        [&](auto& model) {
          auto& v = member(model);
          binary::read_vector(in, v, what);
          return v.size();
        },
        models);
  };
  const std::size_t history_size = read_histories(
      bond_model_, [](auto& m) -> auto& { return m.history; }, "bond histories");
  std::uint64_t broken = 0;
  binary::read(in, broken, "broken bond count");
  if (wraps_.size() != n || bond_state.size() != bonds_.i.size() || history_size != bonds_.i.size())
    fail_input("checkpoint does not match this packing's particles and bonds");
  // Back to the engine's bond order.
  const auto to_engine_order = [&](auto& v) {
    auto input_order = v;
    for (std::size_t b = 0; b < v.size(); ++b) v[b] = input_order[static_cast<std::size_t>(bond_input_index_[b])];
  };
  to_engine_order(bond_state);
  std::visit([&](auto& model) { to_engine_order(model.history); }, bond_model_);
  bonds_.state = std::move(bond_state);
  broken_bonds_ = broken;
  binary::read_vector(in, walls_, "walls");
  const std::size_t wall_history_size = read_histories(
      model_, [](auto& m) -> auto& { return m.wall_history; }, "wall contact histories");
  binary::read_vector(in, wall_force_, "wall forces");
  if (wall_history_size != n * walls_.size() || wall_force_.size() != walls_.size())
    fail_input("checkpoint is damaged: wall data do not match");
  for (auto* v : {&P.position, &P.velocity, &P.angular_velocity, &P.force, &P.torque})
    if (v->size() != n) fail_input("checkpoint is damaged: array sizes differ");
  if (density_.size() != (input_has_density_ ? n : 0))
    fail_input(input_has_density_ ? "checkpoint was written by an engine whose packing had no per-particle densities; "
                                    "this one has them"
                                  : "checkpoint was written by an engine whose packing had per-particle densities; "
                                    "this one has none");
  if (P.radius.size() != n || P.type.size() != n || P.fixed.size() != n || original_index_.size() != n)
    fail_input("checkpoint is damaged: array sizes differ");
  for (const int t : P.type)
    if (t < 0 || static_cast<std::size_t>(t) >= type_damping_.size())
      fail_input(fmt::format("checkpoint is damaged: particle type {} (the packing has types 0 to {})", t,
                             type_damping_.size() - 1));
  for (std::size_t k = 0; k < n; ++k) update_mass(k);
  masses_changed();
  neighbors_.load(in);
  std::visit([&](auto& model) { binary::read_vector(in, model.history, "contact histories"); }, model_);
  // An engine that keeps no pair histories (pair_histories_) writes none; one written before
  // that holds a zero history per listed pair, read and dropped.
  const std::size_t pair_history_size = std::visit([&](auto& m) { return m.history.size(); }, model_);
  if (neighbors_.particle_count() != n ||
      (pair_history_size != neighbors_.pair_count() && (pair_histories_ || pair_history_size != 0)))
    fail_input("checkpoint is damaged: contact histories do not match the neighbour list");
  if (!pair_histories_) std::visit([&](auto& m) { release_memory(m.history); }, model_);
  binary::read_vector(in, breaks_, "bond breaks");
  binary::read(in, sorted_index_distance_, "particle sort");
  binary::read(in, resorts_, "particle sorts");
  // The particle order is the saved one: every index must be there once.
  {
    std::vector<std::uint8_t> seen(n, 0);
    for (const int k : original_index_) {
      if (k < 0 || static_cast<std::size_t>(k) >= n || seen[static_cast<std::size_t>(k)])
        fail_input("checkpoint is damaged: the particle order is not a permutation");
      seen[static_cast<std::size_t>(k)] = 1;
    }
  }
  mark_bonded_pairs();
  partition_work();
}

}  // namespace packlab::dem
