#include "packlab/generate/ls.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "packlab/core/error.hpp"
#include "packlab/core/neighbor_list.hpp"
#include "packlab/core/spatial_sort.hpp"
#include "packlab/io/options.hpp"

namespace packlab::generate {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// The skin's adaptation at a block's end: it grows by skin_grow while transfers outnumber half
// the collisions and the lists hold fewer than skin_grow_below_fill entries per sphere (transfers
// cost a cell search), and shrinks by skin_shrink when transfers are rare (under a tenth of the
// collisions) or the lists hold more than skin_shrink_above_fill (each prediction reads them).
constexpr double skin_grow_below_fill = 12.0, skin_shrink_above_fill = 20.0;
constexpr double skin_grow = 1.5, skin_shrink = 0.8;

int floor_div(int a, int n) { return a >= 0 ? a / n : -((-a + n - 1) / n); }

// Collision time (eq. 8) if it is below `horizon`, else +inf. f(t) = A t^2 + 2 B t + C =
// |dx + dv t|^2 - (sigma + sdot t)^2. Lower bounds reject most pairs without sqrt or division:
// for B < 0 and A >= 0 the root C / (-B + sqrt(B^2 - AC)) is >= C / (-2B); for B >= 0 and A < 0
// the root (B + sqrt(B^2 - AC)) / (-A) is >= 2B / (-A) when C >= 0.
[[gnu::always_inline]] inline double collision_time_below(const Vec3& dx, const Vec3& dv, double sigma, double sdot,
                                                          double horizon) {
  const double a = norm2(dv) - sdot * sdot;
  const double b = dot(dx, dv) - sigma * sdot;
  const double c = norm2(dx) - sigma * sigma;
  if (b < 0.0) {
    if (c <= 0.0) return 0.0;
    if (a >= 0.0 && c >= -2.0 * b * horizon) return inf;
    const double disc = b * b - a * c;
    if (disc < 0.0) return inf;
    return c / (-b + std::sqrt(disc));
  }
  if (a >= 0.0) return inf;
  if (c >= 0.0 && 2.0 * b >= -a * horizon) return inf;
  const double disc = std::max(0.0, b * b - a * c);
  return (b + std::sqrt(disc)) / (-a);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Parameters

void LsParams::validate() const {
  LsParams copy = *this;
  io::ConfigSchema declared("generate ls");
  io::add_ls_params(declared, copy);
  declared.validate();
  require(target_volume_fraction >= 0.0 && target_volume_fraction < 1.0, "target_volume_fraction",
          target_volume_fraction, "in [0, 1) (0 = grow until jammed)");
  require(max_blocks >= 0, "max_blocks", static_cast<double>(max_blocks), ">= 0");
  require(max_events_per_particle > 0.0, "max_events_per_particle", max_events_per_particle, "> 0");
  require(separation_boost >= 1.0 && separation_boost <= 100.0, "separation_boost", separation_boost, "in [1, 100]");
  require(neighbor_skin > 0.0 && neighbor_skin <= 1.0, "neighbor_skin", neighbor_skin, "in (0, 1] diameters");
  if (growth_rate == 0.0)
    require(max_blocks > 0, "max_blocks", static_cast<double>(max_blocks),
            "> 0 when growth_rate = 0 (nothing else would stop the run)");
}

std::string ls_stop_name(LsStop stop) {
  switch (stop) {
    case LsStop::target_reached:
      return "target_reached";
    case LsStop::jammed:
      return "jammed";
    case LsStop::max_blocks:
      return "max_blocks";
    case LsStop::max_events:
      return "max_events";
  }
  return "?";
}

// ---------------------------------------------------------------------------------------------
// Two-body kernels

double LsSimulation::collision_time(const Vec3& dx, const Vec3& dv, double sigma, double sigma_dot) {
  // Approaching surfaces: the smaller positive root, written without cancellation. Receding
  // surfaces meet again only if the growth wins (A < 0), at the larger root.
  return collision_time_below(dx, dv, sigma, sigma_dot, inf);
}

void LsSimulation::collide(Vec3& vi, Vec3& vj, const Vec3& n, double sigma_dot, double boost) {
  const double u = dot(vj - vi, n);
  const double dvn = u - boost * sigma_dot;
  vi += n * dvn;
  vj -= n * dvn;
}

// ---------------------------------------------------------------------------------------------
// Cells of bounding-sphere centres, one grid per class (built in ls_setup.cpp).

// The cell coordinates of i's bounding-sphere centre in its class grid. Computed where they are
// needed instead of stored (4 B per sphere, issue #14): the same centre always gives the same cell.
void LsSimulation::cell_coords(int i, int c[3]) const {
  const Grid& gr = grid_[class_of(body_[i])];
  const Vec3& x = center_[i];
  for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>(std::floor(x[a] / gr.h[a])), 0, gr.n[a] - 1);
}

int LsSimulation::cell_of(int i) const {
  const Grid& gr = grid_[class_of(body_[i])];
  int c[3];
  cell_coords(i, c);
  return c[0] + gr.n[0] * (c[1] + gr.n[1] * c[2]);
}

void LsSimulation::insert(int i) {
  Grid& gr = grid_[class_of(body_[i])];
  const int cell = cell_of(i);
  next_[i] = gr.head[cell];
  gr.head[cell] = i;
}

// Before i's centre moves: the cell is found from it.
void LsSimulation::remove(int i) {
  Grid& gr = grid_[class_of(body_[i])];
  int* link = &gr.head[cell_of(i)];
  while (*link != i) link = &next_[*link];  // a cell holds a few particles
  *link = next_[i];
}

// ---------------------------------------------------------------------------------------------
// Neighbour lists (symmetric: (j, image) in i's list <=> (i, -image) in j's list).

void LsSimulation::add_neighbor(int i, std::uint32_t entry) {
  if (list_fill_[i] == list_cap_[i]) relocate_list(i);
  list_[list_base_[i] + list_fill_[i]++] = entry;
}

// The room of a list of `fill` entries when the lists are laid out or packed: one spare entry and
// one per 16 (a transfer adds and drops neighbours). These, the pool's spare of a thirty-second
// (build_lists) and the growth of a full segment by half (relocate_list) set where segments lie,
// never the entries' order, so the run is the same bit for bit: with them and the cells found
// from the centres instead of stored, the largest memory of a 10^4-sphere slow run to jamming at
// G = 0.04 fell from 214 to 204 bytes per sphere, with the same phi, collisions and transfers
// (bench_ls; was 1 + fill / 8, a pool spare of an eighth and doubling).
namespace {
std::size_t list_room(std::size_t fill) { return std::min<std::size_t>(65535, fill + 1 + fill / 16); }
}  // namespace

// i's segment is full: it moves to the pool's end with half as much room again (its old place stays
// unused). The pool keeps spare room for this (build_lists); when that is used up, the segments
// are first packed together if the unused places add up to a thirty-second of the pool, else (or
// if that is still not enough) the pool grows by a sixteenth, in place where realloc can (counted
// in the peak). Packing brought the largest memory of a 10^4-sphere run to jamming at G = 3 from
// 210 to 195 bytes per sphere (190 since the cells are computed, not stored; issue #14: at most
// 200; bench_ls).
void LsSimulation::relocate_list(int i) {
  const std::size_t cap = list_cap_[i];
  const std::size_t cap2 = std::max<std::size_t>(4, cap + cap / 2);
  if (cap2 > 65535 || list_end_ + cap2 > std::numeric_limits<std::uint32_t>::max())
    throw std::runtime_error("LsSimulation: neighbour list too long (the skin is too large for this box)");
  if (list_end_ + cap2 > list_.size()) pack_lists();
  if (list_end_ + cap2 > list_.size()) {
    list_.resize(list_end_ + cap2 + list_.size() / 16);
    note_memory(0);
  }
  std::copy_n(list_.data() + list_base_[i], list_fill_[i], list_.data() + list_end_);
  list_base_[i] = static_cast<std::uint32_t>(list_end_);
  list_cap_[i] = static_cast<std::uint16_t>(cap2);
  list_end_ += cap2;
}

// Moves every segment down over the unused places that relocations left, in pool order (each
// moves to a lower or the same place, so one pass in place does it), with its entries in their
// order and its room cut to what build_lists gives: the lists, and so the run, stay the same bit
// for bit. The pool order is found window by window (the pool cut into `pack_windows` equal
// spans, the segments starting in one span sorted by start, the spans in order) rather than by
// one index of every particle: that index, 4 B per sphere, stood beside the full pool when a run
// reaches its largest memory (issue #14); a window's index holds about an eighth of it. At 10^4
// spheres the largest memory fell by 3.5-4 B per sphere (G = 3: 186 -> 182, G = 0.04: 200.0 ->
// 196.6, bimodal to c = 0.6: 208 -> 205) for eight scans of the bases per pack: the bimodal run
// packs 3,400 times and took 22.55 against 21.35 CPU s (5 alternating runs each, bench_ls; 21.92 against
// 21.44 without the first pair, 25.06 / 20.99).
void LsSimulation::pack_lists() {
  const std::size_t n = body_.size();
  std::size_t used = 0;
  for (std::size_t i = 0; i < n; ++i) used += list_cap_[i];
  if (32 * (list_end_ - used) < list_.size()) return;
  constexpr std::size_t pack_windows = 8;
  const std::size_t width = list_end_ / pack_windows + 1;
  std::array<std::size_t, pack_windows> members{};
  for (std::size_t i = 0; i < n; ++i) ++members[list_base_[i] / width];
  std::vector<int> window(*std::max_element(members.begin(), members.end()));
  note_memory(window.size() * sizeof(int));
  std::size_t end = 0;
  for (std::size_t w = 0; w < pack_windows; ++w) {
    // Segments already moved start below this span (end <= their old start), so they are not met again.
    const std::size_t lo = w * width;
    std::size_t m = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (list_base_[i] >= lo && list_base_[i] < lo + width) window[m++] = static_cast<int>(i);
    std::sort(window.begin(), window.begin() + static_cast<std::ptrdiff_t>(m),
              [&](int a, int b) { return list_base_[a] < list_base_[b]; });
    for (std::size_t k = 0; k < m; ++k) {
      const int i = window[k];
      const std::uint32_t* from = list_.data() + list_base_[i];
      std::copy(from, from + list_fill_[i], list_.data() + end);  // end <= base: std::copy allows the overlap
      list_base_[i] = static_cast<std::uint32_t>(end);
      list_cap_[i] =
          static_cast<std::uint16_t>(std::min<std::size_t>(list_cap_[i], list_room(list_fill_[i])));  // as build_lists
      end += list_cap_[i];
    }
  }
  list_end_ = end;
}

LsSimulation::EntryPool& LsSimulation::EntryPool::operator=(const EntryPool& o) {
  if (this != &o) {
    resize(o.n_);
    if (o.n_ > 0) std::copy_n(o.p_, o.n_, p_);
  }
  return *this;
}

void LsSimulation::EntryPool::resize(std::size_t n) {
  if (n == 0) {
    release();
    return;
  }
  void* q = std::realloc(p_, n * sizeof(std::uint32_t));
  if (q == nullptr) throw std::bad_alloc();
  p_ = static_cast<std::uint32_t*>(q);
  n_ = n;
}

void LsSimulation::drop_neighbor(int i, std::uint32_t entry) {
  std::uint32_t* l = list_.data() + list_base_[i];
  const int n = list_fill_[i];
  for (int q = 0; q < n; ++q)
    if (l[q] == entry) {
      l[q] = l[n - 1];
      --list_fill_[i];
      return;
    }
  throw std::logic_error("LsSimulation: neighbour lists are not symmetric");
}

// Calls visit(j, image code) for every sphere j whose bounding sphere overlaps i's (j > i only
// with only_greater), in the order of the cell stencil.
template <class Visit>
void LsSimulation::scan_neighbors(int i, bool only_greater, Visit&& visit) {
  const int k = class_of(body_[i]);
  const Grid& gk = grid_[k];
  const Vec3 xi = center_[i];
  int c[3];
  cell_coords(i, c);
  const double bi = bound_[i];
  for (int m = 0; m < nclass_; ++m) {
    const Grid& gm = grid_[m];
    const double reach = reach_[k * nclass_ + m];
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      if (m == k && reach <= gk.h[a]) {
        lo[a] = c[a] - 1;
        hi[a] = c[a] + 1;
      } else {
        lo[a] = static_cast<int>(std::floor((c[a] * gk.h[a] - reach) / gm.h[a]));
        hi[a] = static_cast<int>(std::floor(((c[a] + 1) * gk.h[a] + reach) / gm.h[a]));
      }
    }
    for (int uz = lo[2]; uz <= hi[2]; ++uz) {
      const int sz = floor_div(uz, gm.n[2]);
      const int wz = uz - sz * gm.n[2];
      for (int uy = lo[1]; uy <= hi[1]; ++uy) {
        const int sy = floor_div(uy, gm.n[1]);
        const int wy = uy - sy * gm.n[1];
        const int row = gm.n[0] * (wy + gm.n[1] * wz);
        for (int ux = lo[0]; ux <= hi[0]; ++ux) {
          const int sx = floor_div(ux, gm.n[0]);
          const int wx = ux - sx * gm.n[0];
          if (sx < -1 || sx > 1 || sy < -1 || sy > 1 || sz < -1 || sz > 1)
            throw std::logic_error("LsSimulation: neighbour beyond the first periodic image");
          const int code = image_code(sx, sy, sz);
          const Vec3& off = offset_[code];
          for (int j = gm.head[wx + row]; j >= 0; j = next_[j]) {
            if (j == i || (only_greater && j < i)) continue;
            const Vec3 d = center_[j] + off - xi;
            const double r = bi + bound_[j];
            if (norm2(d) < r * r) visit(j, code);
          }
        }
      }
    }
  }
}

void LsSimulation::find_neighbors(int i, bool only_greater) {
  scan_neighbors(i, only_greater, [&](int j, int code) {
    add_neighbor(i, static_cast<std::uint32_t>(j) * 32u + static_cast<std::uint32_t>(code));
    add_neighbor(j, static_cast<std::uint32_t>(i) * 32u + static_cast<std::uint32_t>(26 - code));
  });
}

// Two passes over the cells: count each sphere's neighbours, then lay the lists out with that
// many entries plus room for the changes of a block (transfers add and drop neighbours).
void LsSimulation::build_lists() {
  const std::size_t n = body_.size();
  const double s = s0_;
  for (int c = 0; c < 27; ++c) offset_[c] = box_.shift_vector(image_of_code(c));
  bound_.resize(n);
  for (std::size_t i = 0; i < n; ++i) bound_[i] = rho_of(body_[i]) * s + skin_[class_of(body_[i])];
  list_fill_.assign(n, 0);
  for (int i = 0; i < static_cast<int>(n); ++i)
    scan_neighbors(i, true, [&](int j, int) {
      ++list_fill_[i];
      ++list_fill_[j];
    });
  list_base_.resize(n);
  list_cap_.resize(n);
  std::size_t total = 0;
  for (std::size_t q = 0; q < n; ++q) {
    const std::size_t cap = list_room(list_fill_[q]);
    if (total + cap > std::numeric_limits<std::uint32_t>::max())
      throw std::runtime_error("LsSimulation: neighbour lists beyond 2^32 entries");
    list_base_[q] = static_cast<std::uint32_t>(total);
    list_cap_[q] = static_cast<std::uint16_t>(cap);
    list_fill_[q] = 0;
    total += cap;
  }
  list_end_ = total;
  list_.resize(total + total / 32 + 64);  // spare room for segments that outgrow theirs
  for (int i = 0; i < static_cast<int>(n); ++i) find_neighbors(i, true);
}

void LsSimulation::transfer(int i) {
  Body& b = body_[i];
  // Leave the old neighbours.
  const std::uint32_t* l = list_.data() + list_base_[i];
  for (int q = 0; q < list_fill_[i]; ++q) {
    const std::uint32_t e = l[q];
    drop_neighbor(static_cast<int>(e >> 5), static_cast<std::uint32_t>(i) * 32u + (26u - (e & 31u)));
  }
  list_fill_[i] = 0;
  // Re-centre the bounding sphere at the (wrapped) current position.
  remove(i);
  b.x = box_.wrap(b.x);
  center_[i] = b.x;
  bound_[i] = rho_of(b) * s_at(b.t) + skin_[class_of(b)];
  insert(i);
  find_neighbors(i, false);
}

// ---------------------------------------------------------------------------------------------
// Event calendar: indexed binary min-heap of one pending event per particle.

// While a block starts, hkey_[i] is i's event time (hpos_ the identity, hid_ empty): the
// sorted order of those times becomes the heap (a sorted array is a heap).
void LsSimulation::heap_build() {
  const int n = static_cast<int>(body_.size());
  hid_.resize(n);
  std::iota(hid_.begin(), hid_.end(), 0);
  std::sort(hid_.begin(), hid_.end(), [&](int a, int b) { return hkey_[a] < hkey_[b]; });
  for (int k = 0; k < n; ++k) hpos_[hid_[k]] = k;
  // hkey_[k] <- hkey_[hid_[k]] in place, cycle by cycle (hid_ marked negative while visited).
  for (int k = 0; k < n; ++k) {
    if (hid_[k] < 0) continue;
    const double first = hkey_[k];
    int q = k;
    for (;;) {
      const int from = hid_[q];
      hid_[q] = -1 - from;
      if (from == k) {
        hkey_[q] = first;
        break;
      }
      hkey_[q] = hkey_[from];
      q = from;
    }
  }
  for (int& h : hid_) h = -1 - h;
}

void LsSimulation::heap_update(int i, double key) {
  int k = hpos_[i];
  const int n = static_cast<int>(hid_.size());
  double* hk = hkey_.data();
  int* hi = hid_.data();
  int* hp = hpos_.data();
  // up
  while (k > 0) {
    const int parent = (k - 1) >> 1;
    if (hk[parent] <= key) break;
    hk[k] = hk[parent];
    hi[k] = hi[parent];
    hp[hi[k]] = k;
    k = parent;
  }
  // down
  for (;;) {
    int child = 2 * k + 1;
    if (child >= n) break;
    if (child + 1 < n && hk[child + 1] < hk[child]) ++child;
    if (hk[child] >= key) break;
    hk[k] = hk[child];
    hi[k] = hi[child];
    hp[hi[k]] = k;
    k = child;
  }
  hk[k] = key;
  hi[k] = i;
  hp[i] = k;
}

// ---------------------------------------------------------------------------------------------
// Prediction: earliest collision with a neighbour, or the transfer time.

void LsSimulation::predict(int i) {
  const Body bi = body_[i];
  const Body* bodies = body_.data();
  const std::uint32_t* l = list_.data() + list_base_[i];
  const int fill = list_fill_[i];
  // The neighbours' lines requested together, before the transfer time is computed (away from
  // the L2 cache, at 10^5 particles and more, one after another each would cost a latency).
  for (int q = 0; q < fill; ++q) __builtin_prefetch(bodies + (l[q] >> 5));
  const double* rho = class_rho_.data();
  const double rho_i = rho[class_of(bi)];
  const double now = bi.t;
  const double g = params_.growth_rate;
  const double s = s_at(now);
  // Transfer: |x + v t - c| = w - rho g t with w = bound - radius now.
  double tau_tr;
  {
    const Vec3 dx = bi.x - center_[i];
    const double w = bound_[i] - rho_i * s;
    const double wdot = -rho_i * g;
    const double a = norm2(bi.v) - wdot * wdot;
    const double b = dot(dx, bi.v) - w * wdot;
    const double c = norm2(dx) - w * w;
    if (c >= 0.0 || w <= 0.0) {
      tau_tr = 0.0;
    } else {
      const double disc = b * b - a * c;
      if (b > 0.0 && disc >= 0.0) {
        tau_tr = -c / (b + std::sqrt(disc));
      } else if (a > 0.0) {
        tau_tr = (std::sqrt(disc) - b) / a;
      } else {
        tau_tr = inf;
      }
      if (g > 0.0) tau_tr = std::min(tau_tr, w / (rho_i * g));
    }
  }
  double best = now + tau_tr;
  int partner = -1;
  for (int q = 0; q < fill; ++q) {
    const std::uint32_t e = l[q];
    const int j = static_cast<int>(e >> 5);
    const Vec3& off = offset_[e & 31u];
    const Body& bj = bodies[j];
    const double dtj = now - bj.t;
    const Vec3 dx{bj.x.x + bj.v.x * dtj + off.x - bi.x.x, bj.x.y + bj.v.y * dtj + off.y - bi.x.y,
                  bj.x.z + bj.v.z * dtj + off.z - bi.x.z};
    const Vec3 dv = bj.v - bi.v;
    const double sig1 = rho_i + rho[class_of(bj)];
    const double tau = collision_time_below(dx, dv, sig1 * s, sig1 * g, best - now);
    // A collision after j's own next event is left to j: j predicts again then.
    if (now + tau < best && now + tau <= event_time(j)) {
      best = now + tau;
      partner = j;
    }
  }
  Event& e = ev_[i];
  e.partner = partner;
  e.stamp = partner >= 0 ? body_[partner].stamp : 0;
  if (hid_.empty())
    hkey_[i] = best;  // a block starts: by particle (heap_build)
  else
    heap_update(i, best);
}

// ---------------------------------------------------------------------------------------------
// Blocks

void LsSimulation::sync_all(double t) {
  for (auto& b : body_) {
    b.x += b.v * (t - b.t);
    b.x = box_.wrap(b.x);
    b.t = 0.0;
  }
}

void LsSimulation::start_block() {
  // The lists are rebuilt below: free them first, so that the re-sort's temporaries do not
  // stack on top of them.
  list_.release();
  // Morton order: neighbours in space are neighbours in memory.
  const double cell = std::max(2.0 * class_rho_[0] * std::max(s0_, 0.05),
                               std::min({box_.length.x, box_.length.y, box_.length.z}) * 1e-4);
  const std::size_t n = body_.size();
  {
    std::vector<Vec3> pos(n);
    for (std::size_t i = 0; i < n; ++i) pos[i] = body_[i].x;
    std::vector<int> order = spatial_order(box_, pos, cell);
    // spatial_order's keys (8 B) and stable-sort buffer (up to 4 B) per particle were alive
    // beside the positions and the order.
    note_memory(n * (sizeof(Vec3) + sizeof(int) + 12));
    // Permute in place, cycle by cycle (slot k takes particle order[k]; visited slots marked
    // by a negative entry).
    for (std::size_t k = 0; k < n; ++k) {
      if (order[k] < 0) continue;
      const Body b0 = body_[k];
      std::size_t q = k;
      for (;;) {
        const auto from = static_cast<std::size_t>(order[q]);
        order[q] = -1 - order[q];
        if (from == k) {
          body_[q] = b0;
          break;
        }
        body_[q] = body_[from];
        q = from;
      }
    }
  }
  build_grids();
  build_lists();
  hid_.clear();
  hkey_.resize(n);
  hpos_.resize(n);
  std::iota(hpos_.begin(), hpos_.end(), 0);
  for (auto& e : ev_) e = Event{-2, 0};
  std::fill(hkey_.begin(), hkey_.end(), inf);
  for (int i = 0; i < static_cast<int>(n); ++i) predict(i);
  heap_build();
  note_memory(0);
  virial_ = 0.0;
}

bool LsSimulation::run_block() {
  const long long n = static_cast<long long>(body_.size());
  const long long budget =
      std::max<long long>(1, static_cast<long long>(params_.events_per_block * static_cast<double>(n)));
  const double boost = params_.separation_boost;
  const double g = params_.growth_rate;
  const long long collisions0 = status_.collisions, transfers0 = status_.transfers;
  long long done = 0;
  double now = 0.0;
  bool reached_end = false;
  Body* bodies = body_.data();
  while (done < budget) {
    const int i = hid_[0];
    const Event e = ev_[i];
    const double e_time = hkey_[0];
    if (e_time >= t_end_) {
      reached_end = std::isfinite(t_end_);
      if (reached_end) now = t_end_;
      break;
    }
    now = e_time;
    Body& bi = bodies[i];
    if (e.partner >= 0) {
      const int j = e.partner;
      if (body_[j].stamp != e.stamp) {  // partner changed velocity since: predict again
        ++status_.stale;
        bi.x += bi.v * (now - bi.t);
        bi.t = now;
        predict(i);
        continue;
      }
      Body& bj = bodies[j];
      bi.x += bi.v * (now - bi.t);
      bi.t = now;
      bj.x += bj.v * (now - bj.t);
      bj.t = now;
      Vec3 d = bj.x - bi.x;
      for (int a = 0; a < 3; ++a) {
        const double l = box_.length[a];
        if (d[a] > 0.5 * l)
          d[a] -= l;
        else if (d[a] < -0.5 * l)
          d[a] += l;
      }
      const double r = norm(d);
      const Vec3 nrm = d * (1.0 / r);
      const double sig1 = rho_of(bi) + rho_of(bj);
      const double u = dot(bj.v - bi.v, nrm);
      virial_ += std::abs(u) * r;  // exchanged momentum (unit masses) times distance, growth part excluded
      collide(bi.v, bj.v, nrm, sig1 * g, boost);
      body_[i].stamp += collision_step;
      body_[j].stamp += collision_step;
      ++status_.collisions;
      ++done;
      predict(i);
      predict(j);
    } else if (e.partner == -1) {
      bi.x += bi.v * (now - bi.t);
      bi.t = now;
      transfer(i);
      ++status_.transfers;
      ++done;
      predict(i);
    } else {
      break;  // nothing can happen any more
    }
  }
  sync_all(now);
  note_memory(0);
  {  // adapt the skin: transfers cost a cell search, large lists cost every prediction
    const double c = static_cast<double>(status_.collisions - collisions0);
    const double t = static_cast<double>(status_.transfers - transfers0);
    const double fill = mean_neighbors();
    const double skin_block = skin_rel_;
    if (t > 0.5 * c && fill < skin_grow_below_fill)
      skin_rel_ = std::min(max_skin_rel, skin_rel_ * skin_grow);
    else if (t < 0.1 * c || fill > skin_shrink_above_fill)
      skin_rel_ = std::max(min_skin_rel, skin_rel_ * skin_shrink);
    // The list-length limit, from the lists the block ended with. The cap at a block's start
    // (build_grids) counts an ideal gas of bounding spheres, and the dense fluid holds more (its
    // contact shell): 13.5 per sphere at the end of the bimodal growth to c = 0.6 under a limit of
    // 12 (205 B per sphere). The block's bounding radius per unit radius, beta = s + 2 skin s_ref
    // (s at the block's end, the block's skin), is scaled by cbrt(limit / fill) as the gas's count
    // would be: this shrinks an over-full skin and keeps a growing one from overshooting.
    if (params_.neighbor_list_limit > 0.0 && fill > 0.0) {
      const double s_end = s_at(now);
      const double beta = s_end + 2.0 * skin_block * skin_scale(s0_);
      const double beta_limit = beta * std::cbrt(params_.neighbor_list_limit / fill);
      skin_rel_ = std::min(skin_rel_, std::max(min_skin_rel, (beta_limit - s_end) / (2.0 * skin_scale(s_end))));
    }
  }
  status_.time += now;
  ++status_.blocks;
  double sum_v2 = 0.0;
  for (const auto& b : body_) sum_v2 += norm2(b.v);
  const double kinetic = 0.5 * sum_v2;
  status_.reduced_pressure = now > 0.0 ? 1.0 + virial_ / (2.0 * kinetic * now) : 1.0;
  const double f = std::sqrt(3.0 * static_cast<double>(n) * v_thermal_ * v_thermal_ / sum_v2);
  for (auto& b : body_) b.v *= f;
  bool stop = false;
  if (reached_end && target_in_block_) {
    s0_ = std::cbrt(params_.target_volume_fraction / phi1_);
    status_.stop = LsStop::target_reached;
    stop = true;
  } else {
    s0_ = s_at(now);
  }
  status_.scale = s0_;
  status_.volume_fraction = phi1_ * s0_ * s0_ * s0_;
  if (!stop && status_.reduced_pressure >= params_.max_reduced_pressure) {
    status_.stop = LsStop::jammed;
    stop = true;
  }
  if (!stop && static_cast<double>(status_.events()) >= params_.max_events_per_particle * static_cast<double>(n)) {
    status_.stop = LsStop::max_events;
    stop = true;
  }
  return !stop;
}

LsStatus LsSimulation::run(const std::function<void(const LsStatus&)>& on_block) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  const double seconds0 = status_.seconds, cpu0 = status_.cpu_seconds;
  if (stopped_) return status_;
  if (params_.target_volume_fraction > 0.0 && status_.volume_fraction >= params_.target_volume_fraction) {
    status_.stop = LsStop::target_reached;
    return status_;
  }
  long blocks = 0;
  for (;;) {
    start_block();
    const bool go_on = run_block();
    ++blocks;
    status_.seconds = seconds0 + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    status_.cpu_seconds = cpu0 + static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    stopped_ = !go_on;
    if (on_block) on_block(status_);
    if (!go_on) break;
    if (params_.max_blocks > 0 && blocks >= params_.max_blocks) {
      status_.stop = LsStop::max_blocks;
      break;
    }
  }
  return status_;
}

}  // namespace packlab::generate
