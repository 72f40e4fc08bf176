// Linked cells + Verlet neighbour list with a skin (half list: each pair once).
//
// A pair (i, j, image) is listed when |r_j + image*L - r_i| < r_i + r_j + reach + skin, where
// `reach` is how far beyond touching the interaction acts (0 for contact-only laws). Images are
// enumerated explicitly through the cell stencil instead of by the minimum-image rule, so
// boxes down to one interaction range per periodic axis are handled (several images of the
// same particle can then be neighbours). The list rebuilds itself when any particle moved
// more than half the skin (radius growth counted), see needs_rebuild().
#pragma once

#include <array>
#include <cstdint>
#include <istream>
#include <ostream>
#include <vector>

#include "packlab/core/box.hpp"
#include "packlab/core/vec3.hpp"

namespace packlab {

// Image code 0..26 <-> shift (sx, sy, sz) in {-1,0,1}^3; 13 is the unshifted image.
inline constexpr int image_code(int sx, int sy, int sz) { return (sx + 1) + 3 * (sy + 1) + 9 * (sz + 1); }
inline constexpr std::array<int, 3> image_of_code(int code) { return {code % 3 - 1, (code / 3) % 3 - 1, code / 9 - 1}; }
inline constexpr int unshifted_image = 13;

class NeighborList {
 public:
  explicit NeighborList(double skin = 0.0) : skin_(skin) {}

  void set_skin(double skin) { skin_ = skin; }
  double skin() const { return skin_; }
  // Interaction range beyond touching [m]; listed, but not part of the rebuild criterion.
  void set_reach(double reach) { reach_ = reach; }
  double reach() const { return reach_; }

  // Wraps `position` into the box along periodic axes and rebuilds. Throws InputError if a
  // periodic box edge is shorter than the largest interaction range (2 r_max + skin).
  // `threads` > 0 builds in parallel; the result does not depend on the thread count.
  // `wraps` (optional, one entry per particle) accumulates the box lengths each particle was
  // wrapped by, so callers can keep unwrapped trajectories and bond images.
  void build(const Box& box, std::vector<Vec3>& position, const std::vector<double>& radius, int threads = 1,
             std::vector<std::array<int, 3>>* wraps = nullptr);

  // True when some pair may have come within contact range without being listed.
  bool needs_rebuild(const std::vector<Vec3>& position, const std::vector<double>& radius) const;

  std::size_t pair_count() const { return partner_.size(); }
  std::size_t particle_count() const { return first_.empty() ? 0 : first_.size() - 1; }
  // Pairs of particle i are [first(i), first(i+1)); partner j > i, or j == i for a self image.
  int first(int i) const { return first_[i]; }
  const std::vector<int>& first_pairs() const { return first_; }
  const std::vector<int>& partner() const { return partner_; }
  const std::vector<std::uint8_t>& image() const { return image_; }
  // Index of each current pair in the list before the last rebuild, or -1 if it is new:
  // lets callers carry per-pair history (shear springs) across rebuilds. Empty after
  // release_history_map() until the next build.
  const std::vector<int>& previous_index() const { return previous_index_; }
  // Whether build() makes the map above (default: yes). A caller that keeps no per-pair
  // history turns it off: the map is then left empty.
  void set_history_map(bool on) { map_histories_ = on; }
  // Frees the map above, for a caller that has carried its histories over (it would otherwise
  // be kept until the next build: 4 bytes per listed pair).
  void release_history_map();
  // Renumbers the particles: particle i becomes new_index[i] (a permutation). The same pairs
  // are then listed under the new numbers as a build lists them (each pair under the smaller
  // index, each particle's partners in ascending order), with the positions and radii at the
  // build renumbered too, so the list stays valid without a rebuild. source[p] is the index
  // that new pair p had before; reversed[p] is 1 where its two particles swapped roles (its
  // image code is then that of the opposite shift, and a per-pair history oriented from i to
  // j must be reversed).
  void renumber(const std::vector<int>& new_index, std::vector<int>& source, std::vector<std::uint8_t>& reversed);
  // Mean |j - i| over the listed pairs: how far apart in memory neighbours lie.
  double mean_index_distance() const;
  // Displacement of image code c in the box the list was built for.
  const Vec3& image_offset(int code) const { return offsets_[code]; }
  long builds() const { return builds_; }
  // Heap bytes held (capacities): per particle (index, positions and radii at the build) and
  // per listed pair (partner, image, the history map unless released). The cells and the
  // per-thread lists of a build live only while it runs.
  struct Memory {
    std::size_t per_particle_arrays = 0, per_pair_arrays = 0;
  };
  Memory memory() const;

  // Exact state (pairs and the positions/radii at the last build) for checkpoints.
  void save(std::ostream& out) const;
  void load(std::istream& in);

 private:
  double skin_;
  double reach_ = 0.0;
  std::vector<int> first_;
  std::vector<int> partner_;
  std::vector<std::uint8_t> image_;
  std::vector<int> previous_index_;
  bool map_histories_ = true;
  std::array<Vec3, 27> offsets_{};
  std::vector<Vec3> position_at_build_;
  std::vector<double> radius_at_build_;
  long builds_ = 0;
};

// Every pair within range r_i + r_j + skin by brute force over all pairs and the images in
// {-1,0,1}^3 (periodic axes only); sorted by (i, j, image). For tests and validation.
struct PairEntry {
  int i, j, image;
  friend bool operator==(const PairEntry&, const PairEntry&) = default;
  friend auto operator<=>(const PairEntry&, const PairEntry&) = default;
};
std::vector<PairEntry> brute_force_pairs(const Box& box, const std::vector<Vec3>& position,
                                         const std::vector<double>& radius, double skin);
std::vector<PairEntry> sorted_pairs(const NeighborList& list);

}  // namespace packlab
