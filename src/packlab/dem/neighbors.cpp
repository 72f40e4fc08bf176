// The neighbour list seen by the engine: rebuilt with the contact histories carried over, and
// the listed pairs that a bond holds (the contact law is off for them).
#include <algorithm>
#include <cmath>

#include "packlab/dem/engine.hpp"

namespace packlab::dem {

void Engine::refresh_neighbors() {
  neighbors_.build(packing_.box, particles_.position, particles_.radius, threads_, &wraps_);
  if (pair_histories_) {  // else the list keeps no map and the pairs no history
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
    neighbors_.release_history_map();
  }
  if (config_.resort_particles && bonds_.i.empty()) {
    // A gas loses its order as it diffuses: sort again once neighbours lie 1.5 times as far
    // apart in memory as after the last sort (measured on the list just built).
    const double distance = neighbors_.mean_index_distance();
    if (sorted_index_distance_ <= 0.0)
      sorted_index_distance_ = distance;
    else if (distance > 1.5 * sorted_index_distance_)
      resort();
  }
  mark_bonded_pairs();
  partition_work();
}

std::array<int, 3> Engine::bond_image_now(std::size_t b) const {
  const auto& wi = wraps_[static_cast<std::size_t>(bonds_.i[b])];
  const auto& wj = wraps_[static_cast<std::size_t>(bonds_.j[b])];
  return {bonds_.image[b][0] + wj[0] - wi[0], bonds_.image[b][1] + wj[1] - wi[1], bonds_.image[b][2] + wj[2] - wi[2]};
}

Vec3 Engine::bond_vector(std::size_t b) const {
  const auto& x = particles_.position;
  return x[static_cast<std::size_t>(bonds_.j[b])] + packing_.box.shift_vector(bond_image_now(b)) -
         x[static_cast<std::size_t>(bonds_.i[b])];
}

int Engine::listed_pair_of(std::size_t b) const {
  auto s = bond_image_now(b);
  int i = bonds_.i[b], j = bonds_.j[b];
  if (j < i) {
    std::swap(i, j);
    s = {-s[0], -s[1], -s[2]};
  }
  if (std::abs(s[0]) > 1 || std::abs(s[1]) > 1 || std::abs(s[2]) > 1) return -1;  // out of range
  int code = image_code(s[0], s[1], s[2]);
  // A particle bonded to its own image: the list would hold that pair once, at the image code
  // above the unshifted one (core/neighbor_list.cpp), so the bond's image or its opposite. (The
  // engine refuses boxes shorter than the interaction range, so such a pair is not listed today.)
  if (i == j && code < unshifted_image) code = image_code(-s[0], -s[1], -s[2]);
  const auto& partner = neighbors_.partner();
  const auto& image = neighbors_.image();
  for (int p = neighbors_.first(i); p < neighbors_.first(i + 1); ++p)
    if (partner[p] == j && image[p] == code) return p;
  return -1;
}

void Engine::mark_bonded_pairs() {
  if (bonds_.i.empty()) return;  // pair_bonded_ stays empty: no pair is held
  pair_bonded_.assign(neighbors_.pair_count(), 0);
  for (std::size_t b = 0; b < bonds_.i.size(); ++b) {
    if (bonds_.state[b] != 0) continue;
    const int p = listed_pair_of(b);
    if (p >= 0) pair_bonded_[static_cast<std::size_t>(p)] = 1;
  }
}

}  // namespace packlab::dem
