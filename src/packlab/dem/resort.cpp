// Renumbering the particles of a running engine along the space-filling curve
// (EngineConfig::resort_particles).
//
// The engine sorts its particles once, when it is built, so that neighbours are near each
// other in memory and each thread's range of particles is a compact region of the box. In a
// gas they diffuse: in the void expansion method's Fig. 1 case, by the time the structure
// jams (q ~ 1.3) two threads took 6.4 s for 3,000 steps against 6.2 s for one, and 4.1 s once
// the same state was sorted again (docs/engine.md, "Performance"). A sort is a permutation of
// every per-particle array, the neighbour list renumbered with it (NeighborList::renumber:
// the same pairs, each under its smaller new index, so no rebuild is needed) and the contact
// histories carried along (reversed where a pair's two particles swapped roles: the history
// is oriented from i to j). It runs inside a neighbour rebuild, whose decision and list do not
// depend on the thread count, so neither does the result.
#include <algorithm>

#include "packlab/core/error.hpp"
#include "packlab/core/spatial_sort.hpp"
#include "packlab/dem/engine.hpp"

namespace packlab::dem {

namespace {

// v[k] := v[order[k]] for every k.
template <class T>
void permute(std::vector<T>& v, const std::vector<int>& order) {
  if (v.empty()) return;
  std::vector<T> out(v.size());
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = v[static_cast<std::size_t>(order[k])];
  v.swap(out);
}

}  // namespace

std::vector<int> Engine::curve_order(const std::vector<Vec3>& position, double r_max) const {
  // Cells of about one interaction range with the skin.
  return spatial_order(packing_.box, position, 2.0 * r_max * (1.0 + config_.skin_ratio));
}

void Engine::resort() {
  const std::size_t n = particles_.size();
  // The same curve and cells as at construction, from the positions the rebuild has just
  // wrapped into the box.
  double r_max = 0.0;
  for (const double r : particles_.radius) r_max = std::max(r_max, r);
  const std::vector<int> order = curve_order(particles_.position, r_max);
  std::vector<int> new_index(n);
  for (std::size_t k = 0; k < n; ++k) new_index[static_cast<std::size_t>(order[k])] = static_cast<int>(k);

  ParticleStore& P = particles_;
  permute(P.position, order);
  permute(P.velocity, order);
  permute(P.angular_velocity, order);
  permute(P.force, order);
  permute(P.torque, order);
  permute(P.radius, order);
  permute(P.mass, order);
  permute(P.inverse_mass, order);
  permute(P.inverse_inertia, order);
  permute(P.type, order);
  permute(P.fixed, order);
  permute(original_index_, order);
  permute(density_, order);
  permute(wraps_, order);
  // The step's per-particle scratch is refilled before it is read; nothing to carry.

  std::vector<int> source;
  std::vector<std::uint8_t> reversed;
  neighbors_.renumber(new_index, source, reversed);
  std::visit(
      [&](auto& model) {
        using Law = std::decay_t<decltype(model.law)>;
        using History = typename Law::History;
        if (pair_histories_) {
          std::vector<History> history(source.size());
          for (std::size_t p = 0; p < source.size(); ++p) {
            const History& h = model.history[static_cast<std::size_t>(source[p])];
            history[p] = reversed[p] ? reversed_history<Law>(h) : h;
          }
          model.history.swap(history);
        }
        // Wall contacts: one history per particle and wall.
        const std::size_t walls = walls_.size();
        if (walls > 0) {
          std::vector<History> wall(model.wall_history.size());
          for (std::size_t k = 0; k < n; ++k)
            for (std::size_t m = 0; m < walls; ++m)
              wall[k * walls + m] = model.wall_history[static_cast<std::size_t>(order[k]) * walls + m];
          model.wall_history.swap(wall);
        }
      },
      model_);
  sorted_index_distance_ = neighbors_.mean_index_distance();
  ++resorts_;
}

void Engine::sort_particles() {
  if (!bonds_.i.empty())
    fail_input("sort_particles: a bonded model keeps the order it was built with (its bonds are stored by it)");
  resort();
  mark_bonded_pairs();
  partition_work();
}

}  // namespace packlab::dem
