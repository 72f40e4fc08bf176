#include "packlab/core/neighbor_list.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/memory.hpp"
#include "packlab/core/parallel_errors.hpp"

namespace packlab {

namespace {

struct CellGrid {
  std::array<int, 3> count{1, 1, 1};
  Vec3 lo, size;
  std::array<bool, 3> periodic{};

  int index(const Vec3& p) const {
    int c[3];
    for (int a = 0; a < 3; ++a) {
      // Open axes: particles outside go to edge cells; a non-finite coordinate (a run gone
      // non-finite, stopped at its next measured step) to cell 0, never through an int cast.
      const double k = std::floor((p[a] - lo[a]) / size[a]);
      c[a] = k >= 0.0 ? (k < count[a] - 1 ? static_cast<int>(k) : count[a] - 1) : 0;
    }
    return c[0] + count[0] * (c[1] + count[1] * c[2]);
  }
};

CellGrid make_grid(const Box& box, const std::vector<Vec3>& position, double range) {
  CellGrid g;
  g.periodic = box.periodic;
  const std::size_t n = position.size();
  // Open axes span the particles, so an exploding packing does not pile into one edge cell.
  for (int a = 0; a < 3; ++a) {
    double lo = box.lo[a], extent = box.length[a];
    if (!box.periodic[a] && n > 0) {
      double mn = position[0][a], mx = mn;
      for (const auto& p : position) {
        mn = std::min(mn, p[a]);
        mx = std::max(mx, p[a]);
      }
      lo = mn;
      extent = std::max(mx - mn, range);
    }
    g.lo[a] = lo;
    const double cells = std::floor(extent / range);  // NaN or huge for a run gone non-finite
    g.count[a] = cells >= 1.0 ? (cells < 1048576.0 ? static_cast<int>(cells) : 1048576) : 1;
  }
  // Keep the number of cells proportional to the particle count (sparse, huge boxes).
  const double max_cells = 8.0 * static_cast<double>(n) + 64.0;
  while (static_cast<double>(g.count[0]) * g.count[1] * g.count[2] > max_cells) {
    for (int a = 0; a < 3; ++a) g.count[a] = std::max(1, g.count[a] / 2);
  }
  for (int a = 0; a < 3; ++a) {
    const double extent = box.periodic[a] ? box.length[a] : std::max(range * g.count[a], 0.0);
    g.size[a] = extent / g.count[a];
    if (!box.periodic[a]) g.size[a] = std::max(g.size[a], range);
  }
  return g;
}

}  // namespace

void NeighborList::build(const Box& box, std::vector<Vec3>& position, const std::vector<double>& radius, int threads,
                         std::vector<std::array<int, 3>>* wraps) {
  const int n = static_cast<int>(position.size());
  double r_max = 0.0;
  for (double r : radius) r_max = std::max(r_max, r);
  const double range = 2.0 * r_max + reach_ + skin_;
  for (int a = 0; a < 3; ++a)
    if (box.periodic[a] && box.length[a] < range)
      fail_input(fmt::format(
          "periodic box edge along {} = {:g} m is shorter than the interaction range 2*r_max + reach + skin = {:g} m",
          "xyz"[a], box.length[a], range));
  // The wrap of each particle at this build, as an image code (13: not wrapped; 255: by more
  // than one box length): a wrap changes the image code of the particle's pairs, and the
  // history map below must look for each pair under its code before the wrap.
  std::vector<std::uint8_t> wrap_code;
  bool wrapped_any = false;
  const bool map_history = map_histories_ && first_.size() == static_cast<std::size_t>(n) + 1;
  if (wraps) wraps->resize(position.size(), {0, 0, 0});
  if (map_history) wrap_code.assign(position.size(), static_cast<std::uint8_t>(unshifted_image));
  for (std::size_t k = 0; k < position.size(); ++k) {
    std::array<int, 3> shift{0, 0, 0};
    position[k] = box.wrap(position[k], &shift);
    if (shift == std::array<int, 3>{0, 0, 0}) continue;
    if (wraps)
      for (int a = 0; a < 3; ++a) (*wraps)[k][a] += shift[a];
    if (!map_history) continue;
    wrapped_any = true;
    const bool one_box = std::abs(shift[0]) <= 1 && std::abs(shift[1]) <= 1 && std::abs(shift[2]) <= 1;
    wrap_code[k] = one_box ? static_cast<std::uint8_t>(image_code(shift[0], shift[1], shift[2])) : std::uint8_t{255};
  }
  for (int c = 0; c < 27; ++c) offsets_[c] = box.shift_vector(image_of_code(c));

  const CellGrid grid = make_grid(box, position, range);
  const int cells = grid.count[0] * grid.count[1] * grid.count[2];
  // The cells and the cell-ordered copies live only while the list is built (issue #14: bytes
  // per particle; allocating them costs far less than the scan that fills the list).
  // Counting sort of particles into cells (stable: particles keep index order in a cell).
  std::vector<int> cell_start(static_cast<std::size_t>(cells) + 1, 0);
  std::vector<int> particle_cell(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    particle_cell[i] = grid.index(position[i]);
    ++cell_start[particle_cell[i] + 1];
  }
  for (int c = 0; c < cells; ++c) cell_start[c + 1] += cell_start[c];
  std::vector<int> cell_particles(static_cast<std::size_t>(n));
  {
    std::vector<int> fill(cell_start.begin(), cell_start.end() - 1);
    for (int i = 0; i < n; ++i) cell_particles[fill[particle_cell[i]]++] = i;
  }
  // Positions and radii in cell order: the stencil scan below then reads memory in sequence.
  std::vector<Vec3> cell_position(static_cast<std::size_t>(n));
  std::vector<double> cell_radius(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    cell_position[k] = position[cell_particles[k]];
    cell_radius[k] = radius[cell_particles[k]];
  }

  // Keep the old list to map per-pair history onto the new one.
  const std::vector<int> old_first = std::move(first_);
  const std::vector<int> old_partner = std::move(partner_);
  const std::vector<std::uint8_t> old_image = std::move(image_);

  threads = std::max(1, std::min(threads, std::max(1, n / 256)));
  // Thread 0 lists its chunk straight into partner_ and image_ (the whole list with one
  // thread); the later chunks go to per-thread buffers appended after the region.
  std::vector<std::vector<int>> thread_partner(static_cast<std::size_t>(threads - 1));
  std::vector<std::vector<std::uint8_t>> thread_image(static_cast<std::size_t>(threads - 1));
  // About the last list's share of pairs, with a margin: the count changes little between
  // rebuilds, so thread 0's lists rarely regrow (a first build grows them as it goes).
  partner_.clear();
  image_.clear();
  const std::size_t expected_pairs = old_partner.size() / static_cast<std::size_t>(threads);
  partner_.reserve(expected_pairs + expected_pairs / 16);
  image_.reserve(expected_pairs + expected_pairs / 16);
  first_.assign(n + 1, 0);
  std::vector<int> counts(n, 0);
  // Coincident or deeply overlapping particles would list up to n^2 pairs (memory exhausted,
  // an exception inside the parallel region, an abort): stop once a thread's chunk holds more
  // than max_pairs_per_particle pairs per particle on average, and report the worst particle.
  constexpr long max_pairs_per_particle = 2000;
  int crowded_particle = -1;
  // A thread's list can still outgrow the free memory below that bound (bad_alloc): caught
  // here and rethrown after the region (core/parallel_errors.hpp), not an abort.
  ParallelErrors errors;

#pragma omp parallel num_threads(threads)
  errors.run(omp_get_thread_num(), [&] {
    const int t = omp_get_thread_num();
    auto& tp = t == 0 ? partner_ : thread_partner[t - 1];
    auto& ti = t == 0 ? image_ : thread_image[t - 1];
    tp.clear();
    ti.clear();
    if (t > 0) {  // about the last list's share, as thread 0's (a bad_alloc is caught below)
      tp.reserve(expected_pairs + expected_pairs / 16);
      ti.reserve(expected_pairs + expected_pairs / 16);
    }
    // Static contiguous chunks of i: concatenating the chunks in thread order gives the
    // same list as a serial build.
    const int begin = static_cast<int>(static_cast<long>(n) * t / threads);
    const int end = static_cast<int>(static_cast<long>(n) * (t + 1) / threads);
    // Plain local pointers: inside the parallel region members and captured vectors would be
    // reloaded through `this` after every push_back (possible aliasing), several loads per
    // candidate.
    const int* __restrict slot_particle = cell_particles.data();
    const Vec3* __restrict slot_position = cell_position.data();
    const double* __restrict slot_radius = cell_radius.data();
    const int* __restrict slot_start = cell_start.data();
    const int* __restrict cell_of = particle_cell.data();
    const std::array<Vec3, 27> offsets = offsets_;
    const double skin = skin_ + reach_;  // listing range beyond touching
    const std::size_t pair_limit = static_cast<std::size_t>(max_pairs_per_particle * (end - begin + 1));
    for (int i = begin; i < end; ++i) {
      if (tp.size() > pair_limit) {
#pragma omp critical(packlab_neighbor_crowded)
        if (crowded_particle < 0 || i - 1 < crowded_particle) crowded_particle = i - 1;
        break;
      }
      const Vec3 pi = position[i];
      const double ri = radius[i];
      const double ri_skin = ri + skin;
      const int ci = cell_of[i];
      const int cx = ci % grid.count[0], cy = (ci / grid.count[0]) % grid.count[1],
                cz = ci / (grid.count[0] * grid.count[1]);
      const std::size_t before = tp.size();
      // Lists the particles of cell-ordered range [begin, end) seen through image `code`.
      const auto scan = [&](int first_slot, int end_slot, int code) {
        const Vec3 shifted = pi - offsets[code];
        for (int k = first_slot; k < end_slot; ++k) {
          const int j = slot_particle[k];
          const Vec3 d = slot_position[k] - shifted;
          const double cut = ri_skin + slot_radius[k];
          // One branch: in range, and each pair once (j > i, or a self image counted once).
          if ((norm2(d) < cut * cut) & ((j > i) | ((j == i) & (code > unshifted_image)))) {
            tp.push_back(j);
            ti.push_back(static_cast<std::uint8_t>(code));
          }
        }
      };
      for (int dz = -1; dz <= 1; ++dz) {
        int nz = cz + dz, sz = 0;
        if (nz < 0 || nz >= grid.count[2]) {
          if (!grid.periodic[2]) continue;
          sz = nz < 0 ? -1 : 1;
          nz -= sz * grid.count[2];
        }
        for (int dy = -1; dy <= 1; ++dy) {
          int ny = cy + dy, sy = 0;
          if (ny < 0 || ny >= grid.count[1]) {
            if (!grid.periodic[1]) continue;
            sy = ny < 0 ? -1 : 1;
            ny -= sy * grid.count[1];
          }
          // Cells are numbered x fastest, so the three cells cx-1..cx+1 of a row are one
          // contiguous range of the cell-ordered arrays: one scan instead of three (most of a
          // build's time goes into visiting nearly empty cells). Rows that wrap in x are
          // visited cell by cell, each with its own image.
          const int row = grid.count[0] * (ny + grid.count[1] * nz);
          if (cx >= 1 && cx + 1 < grid.count[0]) {
            scan(slot_start[row + cx - 1], slot_start[row + cx + 2], image_code(0, sy, sz));
            continue;
          }
          for (int dx = -1; dx <= 1; ++dx) {
            int nx = cx + dx, sx = 0;
            if (nx < 0 || nx >= grid.count[0]) {
              if (!grid.periodic[0]) continue;
              sx = nx < 0 ? -1 : 1;
              nx -= sx * grid.count[0];
            }
            // With fewer than three cells on an axis the same cell is visited with
            // different shifts: each visit is a distinct periodic image.
            scan(slot_start[row + nx], slot_start[row + nx + 1], image_code(sx, sy, sz));
          }
        }
      }
      // Sort each particle's partners (insertion sort: a dozen entries, no allocation) so
      // the list does not depend on the cell grid and old pairs can be matched to new ones.
      const std::size_t count = tp.size() - before;
      for (std::size_t a = before + 1; a < tp.size(); ++a) {
        const int pj = tp[a];
        const std::uint8_t pc = ti[a];
        std::size_t b = a;
        for (; b > before && (tp[b - 1] > pj || (tp[b - 1] == pj && ti[b - 1] > pc)); --b) {
          tp[b] = tp[b - 1];
          ti[b] = ti[b - 1];
        }
        tp[b] = pj;
        ti[b] = pc;
      }
      counts[i] = static_cast<int>(count);
    }
  });
  if (errors.failed()) {  // no half-built list survives
    first_.clear();
    partner_.clear();
    image_.clear();
  }
  errors.rethrow();
  if (crowded_particle >= 0) {
    first_.clear();  // no half-built list survives
    partner_.clear();
    image_.clear();
    fail_input(
        fmt::format("neighbour search: more than {} particles within interaction range of each particle on average "
                    "(particle {} at ({:g}, {:g}, {:g}) has {} partners): coincident or heavily overlapping particles",
                    max_pairs_per_particle, crowded_particle, position[crowded_particle].x,
                    position[crowded_particle].y, position[crowded_particle].z, counts[crowded_particle]));
  }
  for (int i = 0; i < n; ++i) first_[i + 1] = first_[i] + counts[i];
  partner_.reserve(first_[n]);
  image_.reserve(first_[n]);
  for (int t = 0; t + 1 < threads; ++t) {
    partner_.insert(partner_.end(), thread_partner[t].begin(), thread_partner[t].end());
    image_.insert(image_.end(), thread_image[t].begin(), thread_image[t].end());
  }
  // Thread 0's list grows by doubling when its share outgrows the reservation: give back room
  // beyond an eighth of the size (issue #14: bytes per listed pair; a list that doubled once
  // kept up to twice what it needs for the rest of the run).
  if (partner_.capacity() > partner_.size() + partner_.size() / 8) {
    partner_.shrink_to_fit();
    image_.shrink_to_fit();
  }

  // Map new pairs onto old ones (both lists are sorted per i, by partner and then image).
  // Wrapping r_i by s_i and r_j by s_j box lengths (r' = r - s L) turns the pair seen through
  // image c into the same pair seen through image c + s_j - s_i: the old list holds it under
  // c_new - s_j + s_i. For one partner that is the same shift of every code, so the old codes
  // looked for stay in ascending order and the merge below still walks forward.
  if (map_histories_)
    previous_index_.assign(partner_.size(), -1);
  else
    release_memory(previous_index_);
  if (map_history) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (int i = 0; i < n; ++i) {
      int o = old_first[i];
      const int o_end = old_first[i + 1];
      for (int p = first_[i]; p < first_[i + 1]; ++p) {
        const int j = partner_[p];
        int code = image_[p];
        if (wrapped_any && j != i && (wrap_code[i] != unshifted_image || wrap_code[j] != unshifted_image)) {
          if (wrap_code[i] == 255 || wrap_code[j] == 255) continue;  // moved a box length: no history
          const auto c = image_of_code(code), si = image_of_code(wrap_code[i]), sj = image_of_code(wrap_code[j]);
          const int sx = c[0] - sj[0] + si[0], sy = c[1] - sj[1] + si[1], sz = c[2] - sj[2] + si[2];
          if (std::abs(sx) > 1 || std::abs(sy) > 1 || std::abs(sz) > 1) continue;  // not listable before
          code = image_code(sx, sy, sz);
        }
        while (o < o_end && (old_partner[o] < j || (old_partner[o] == j && old_image[o] < code))) ++o;
        if (o < o_end && old_partner[o] == j && old_image[o] == code) previous_index_[p] = o;
      }
    }
  }
  position_at_build_ = position;
  radius_at_build_ = radius;
  ++builds_;
}

void NeighborList::release_history_map() { release_memory(previous_index_); }

void NeighborList::renumber(const std::vector<int>& new_index, std::vector<int>& source,
                            std::vector<std::uint8_t>& reversed) {
  const int n = static_cast<int>(particle_count());
  const std::size_t pairs = partner_.size();
  // Each pair under the smaller of its two new indices; a self image stays under its particle
  // with its code (a build lists it once, at the code above the unshifted one).
  std::vector<int> owner(pairs);
  std::vector<int> counts(static_cast<std::size_t>(n) + 1, 0);
  source.resize(pairs);
  reversed.assign(pairs, 0);
  for (int i = 0; i < n; ++i)
    for (int p = first_[i]; p < first_[i + 1]; ++p) {
      const int a = new_index[i], b = new_index[partner_[p]];
      owner[p] = std::min(a, b);
      reversed[p] = b < a;
      ++counts[static_cast<std::size_t>(owner[p]) + 1];
    }
  std::vector<int> first(static_cast<std::size_t>(n) + 1, 0);
  for (int i = 0; i < n; ++i) first[i + 1] = first[i] + counts[static_cast<std::size_t>(i) + 1];
  std::vector<int> partner(pairs), fill(first.begin(), first.end() - 1);
  std::vector<std::uint8_t> image(pairs), flip(pairs);
  for (int i = 0; i < n; ++i)
    for (int p = first_[i]; p < first_[i + 1]; ++p) {
      const int q = fill[static_cast<std::size_t>(owner[p])]++;
      const bool swap = reversed[p] != 0;
      partner[q] = swap ? new_index[i] : new_index[partner_[p]];
      // Code c of shift s; the opposite shift -s has code 26 - c.
      image[q] = swap ? static_cast<std::uint8_t>(26 - image_[p]) : image_[p];
      flip[q] = reversed[p];
      source[q] = p;
    }
  // Each particle's partners in the order a build gives (by partner, then image), so that the
  // next build maps the histories across (insertion sort: a dozen entries).
  for (int i = 0; i < n; ++i)
    for (int a = first[i] + 1; a < first[i + 1]; ++a) {
      const int pj = partner[a], ps = source[a];
      const std::uint8_t pc = image[a], pf = flip[a];
      int b = a;
      for (; b > first[i] && (partner[b - 1] > pj || (partner[b - 1] == pj && image[b - 1] > pc)); --b) {
        partner[b] = partner[b - 1];
        image[b] = image[b - 1];
        flip[b] = flip[b - 1];
        source[b] = source[b - 1];
      }
      partner[b] = pj;
      image[b] = pc;
      flip[b] = pf;
      source[b] = ps;
    }
  first_.swap(first);
  partner_.swap(partner);
  image_.swap(image);
  reversed.swap(flip);
  release_memory(previous_index_);
  std::vector<Vec3> position(position_at_build_.size());
  std::vector<double> radius(radius_at_build_.size());
  for (std::size_t i = 0; i < position.size(); ++i) position[static_cast<std::size_t>(new_index[i])] = position_at_build_[i];
  for (std::size_t i = 0; i < radius.size(); ++i) radius[static_cast<std::size_t>(new_index[i])] = radius_at_build_[i];
  position_at_build_.swap(position);
  radius_at_build_.swap(radius);
}

double NeighborList::mean_index_distance() const {
  const int n = static_cast<int>(particle_count());
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int p = first_[i]; p < first_[i + 1]; ++p) sum += static_cast<double>(partner_[p] - i);
  return partner_.empty() ? 0.0 : sum / static_cast<double>(partner_.size());
}

NeighborList::Memory NeighborList::memory() const {
  Memory m;
  m.per_particle_arrays = heap_bytes(first_) + heap_bytes(position_at_build_) + heap_bytes(radius_at_build_);
  m.per_pair_arrays = heap_bytes(partner_) + heap_bytes(image_) + heap_bytes(previous_index_);
  return m;
}

bool NeighborList::needs_rebuild(const std::vector<Vec3>& position, const std::vector<double>& radius) const {
  const std::size_t n = position.size();
  if (position_at_build_.size() != n || radius_at_build_.size() != n) return true;
  // A listed-out pair can come into range when the two moved towards each other and grew:
  // 2*max displacement + 2*max growth must stay below the skin.
  double max_disp2 = 0.0, max_growth = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    max_disp2 = std::max(max_disp2, norm2(position[i] - position_at_build_[i]));
    max_growth = std::max(max_growth, radius[i] - radius_at_build_[i]);
  }
  return 2.0 * (std::sqrt(max_disp2) + max_growth) >= skin_;
}

void NeighborList::save(std::ostream& out) const {
  binary::write(out, skin_);
  binary::write(out, builds_);
  binary::write_vector(out, first_);
  binary::write_vector(out, partner_);
  binary::write_vector(out, image_);
  binary::write_vector(out, previous_index_);
  binary::write(out, offsets_);
  binary::write_vector(out, position_at_build_);
  binary::write_vector(out, radius_at_build_);
}

void NeighborList::load(std::istream& in) {
  binary::read(in, skin_, "neighbour skin");
  binary::read(in, builds_, "neighbour builds");
  binary::read_vector(in, first_, "neighbour index");
  binary::read_vector(in, partner_, "neighbour partners");
  binary::read_vector(in, image_, "neighbour images");
  binary::read_vector(in, previous_index_, "neighbour history map");
  binary::read(in, offsets_, "image offsets");
  binary::read_vector(in, position_at_build_, "positions at build");
  binary::read_vector(in, radius_at_build_, "radii at build");
  const std::size_t n = position_at_build_.size();
  if (first_.size() != n + 1 || radius_at_build_.size() != n || image_.size() != partner_.size() ||
      (n > 0 && static_cast<std::size_t>(first_[n]) != partner_.size()) || (n > 0 && first_[0] != 0))
    fail_input("checkpoint is damaged: inconsistent neighbour list");
  // The pair loops walk the index along the pairs: it must not decrease.
  for (std::size_t i = 0; i < n; ++i)
    if (first_[i + 1] < first_[i]) fail_input("checkpoint is damaged: inconsistent neighbour list");
  for (int j : partner_)
    if (j < 0 || static_cast<std::size_t>(j) >= n) fail_input("checkpoint is damaged: neighbour index out of range");
}

std::vector<PairEntry> brute_force_pairs(const Box& box, const std::vector<Vec3>& position,
                                         const std::vector<double>& radius, double skin) {
  std::vector<PairEntry> out;
  const int n = static_cast<int>(position.size());
  std::vector<Vec3> wrapped(position);
  for (auto& p : wrapped) p = box.wrap(p);
  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j)
      for (int code = 0; code < 27; ++code) {
        const auto s = image_of_code(code);
        if ((s[0] && !box.periodic[0]) || (s[1] && !box.periodic[1]) || (s[2] && !box.periodic[2])) continue;
        if (j == i && code <= unshifted_image) continue;
        const Vec3 d = wrapped[j] + box.shift_vector(s) - wrapped[i];
        const double cut = radius[i] + radius[j] + skin;
        if (norm2(d) < cut * cut) out.push_back({i, j, code});
      }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<PairEntry> sorted_pairs(const NeighborList& list) {
  std::vector<PairEntry> out;
  const int n = static_cast<int>(list.particle_count());
  for (int i = 0; i < n; ++i)
    for (int p = list.first(i); p < list.first(i + 1); ++p) out.push_back({i, list.partner()[p], list.image()[p]});
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace packlab
