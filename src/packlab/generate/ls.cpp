#include "packlab/generate/ls.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>

#include "packlab/core/error.hpp"
#include "packlab/core/neighbor_list.hpp"
#include "packlab/core/spatial_sort.hpp"
#include "packlab/io/options.hpp"

namespace packlab::generate {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

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

void LsSimulation::insert(int i) {
  Grid& gr = grid_[cls_[i]];
  const int cell = cell_[i];
  if (gr.fill[cell] == gr.cap) {  // rare: double the capacity of every cell
    const int cap2 = gr.cap * 2;
    std::vector<int> slots(gr.fill.size() * cap2, -1);
    for (std::size_t c = 0; c < gr.fill.size(); ++c)
      std::copy_n(gr.slots.begin() + static_cast<long>(c * gr.cap), gr.fill[c],
                  slots.begin() + static_cast<long>(c * cap2));
    gr.slots.swap(slots);
    gr.cap = cap2;
  }
  const int s = gr.fill[cell]++;
  gr.slots[static_cast<std::size_t>(cell) * gr.cap + s] = i;
  slot_[i] = s;
}

void LsSimulation::remove(int i) {
  Grid& gr = grid_[cls_[i]];
  const int cell = cell_[i];
  const int last = --gr.fill[cell];
  int* base = gr.slots.data() + static_cast<std::size_t>(cell) * gr.cap;
  const int moved = base[last];
  base[slot_[i]] = moved;
  slot_[moved] = slot_[i];
}

// ---------------------------------------------------------------------------------------------
// Neighbour lists (symmetric: (j, image) in i's list <=> (i, -image) in j's list).

void LsSimulation::add_neighbor(int i, std::uint32_t entry) {
  const int k = cls_[i];
  if (list_fill_[i] == list_cap_[k]) {  // rare: grow this class's capacity, re-layout
    std::vector<int> cap2 = list_cap_;
    cap2[k] *= 2;
    std::vector<std::size_t> base2(body_.size());
    std::size_t total = 0;
    for (std::size_t q = 0; q < body_.size(); ++q) {
      base2[q] = total;
      total += cap2[cls_[q]];
    }
    std::vector<std::uint32_t> list2(total);
    for (std::size_t q = 0; q < body_.size(); ++q)
      std::copy_n(list_.begin() + static_cast<long>(list_base_[q]), list_fill_[q],
                  list2.begin() + static_cast<long>(base2[q]));
    list_.swap(list2);
    list_base_.swap(base2);
    list_cap_ = cap2;
  }
  list_[list_base_[i] + list_fill_[i]++] = entry;
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

void LsSimulation::find_neighbors(int i, bool only_greater) {
  const int k = cls_[i];
  const Grid& gk = grid_[k];
  const auto& c = cc_[i];
  const Vec3 ci = center_[i];
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
          const int cell = wx + row;
          const int fill = gm.fill[cell];
          const int* members = gm.slots.data() + static_cast<std::size_t>(cell) * gm.cap;
          for (int q = 0; q < fill; ++q) {
            const int j = members[q];
            if (j == i || (only_greater && j < i)) continue;
            const Vec3 d = center_[j] + off - ci;
            const double r = bi + bound_[j];
            if (norm2(d) < r * r) {
              add_neighbor(i, static_cast<std::uint32_t>(j) * 32u + static_cast<std::uint32_t>(code));
              add_neighbor(j, static_cast<std::uint32_t>(i) * 32u + static_cast<std::uint32_t>(26 - code));
            }
          }
        }
      }
    }
  }
}

void LsSimulation::build_lists() {
  const std::size_t n = body_.size();
  const double s = s0_;
  for (int c = 0; c < 27; ++c) offset_[c] = box_.shift_vector(image_of_code(c));
  center_.resize(n);
  bound_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    center_[i] = body_[i].x;  // wrapped by sync_all
    bound_[i] = body_[i].rho * s + skin_[cls_[i]];
  }
  if (list_cap_.size() != static_cast<std::size_t>(nclass_)) list_cap_.assign(nclass_, 16);
  list_base_.resize(n);
  list_fill_.assign(n, 0);
  std::size_t total = 0;
  for (std::size_t q = 0; q < n; ++q) {
    list_base_[q] = total;
    total += list_cap_[cls_[q]];
  }
  list_.assign(total, 0);
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
  b.x = box_.wrap(b.x);
  center_[i] = b.x;
  bound_[i] = b.rho * s_at(b.t) + skin_[cls_[i]];
  remove(i);
  const Grid& gr = grid_[cls_[i]];
  auto& c = cc_[i];
  for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>(std::floor(b.x[a] / gr.h[a])), 0, gr.n[a] - 1);
  cell_[i] = c[0] + gr.n[0] * (c[1] + gr.n[1] * c[2]);
  insert(i);
  find_neighbors(i, false);
}

// ---------------------------------------------------------------------------------------------
// Event calendar: indexed binary min-heap of one pending event per particle.

void LsSimulation::heap_build() {
  const int n = static_cast<int>(body_.size());
  hkey_.resize(n);
  hid_.resize(n);
  hpos_.resize(n);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return ev_[a].time < ev_[b].time; });
  for (int k = 0; k < n; ++k) {  // a sorted array is a heap
    hid_[k] = order[k];
    hkey_[k] = ev_[order[k]].time;
    hpos_[order[k]] = k;
  }
}

void LsSimulation::heap_update(int i) {
  const double key = ev_[i].time;
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
  const double now = bi.t;
  const double g = params_.growth_rate;
  const double s = s_at(now);
  // Transfer: |x + v t - c| = w - rho g t with w = bound - radius now.
  double tau_tr;
  {
    const Vec3 dx = bi.x - center_[i];
    const double w = bound_[i] - bi.rho * s;
    const double wdot = -bi.rho * g;
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
      if (g > 0.0) tau_tr = std::min(tau_tr, w / (bi.rho * g));
    }
  }
  double best = now + tau_tr;
  int partner = -1;
  const Body* bodies = body_.data();
  const Event* ev = ev_.data();
  const std::uint32_t* l = list_.data() + list_base_[i];
  const int fill = list_fill_[i];
  for (int q = 0; q < fill; ++q) {
    const std::uint32_t e = l[q];
    const int j = static_cast<int>(e >> 5);
    const Vec3& off = offset_[e & 31u];
    const Body& bj = bodies[j];
    const double dtj = now - bj.t;
    const Vec3 dx{bj.x.x + bj.v.x * dtj + off.x - bi.x.x, bj.x.y + bj.v.y * dtj + off.y - bi.x.y,
                  bj.x.z + bj.v.z * dtj + off.z - bi.x.z};
    const Vec3 dv = bj.v - bi.v;
    const double sig1 = bi.rho + bj.rho;
    const double tau = collision_time_below(dx, dv, sig1 * s, sig1 * g, best - now);
    // A collision after j's own next event is left to j: j predicts again then.
    if (now + tau < best && now + tau <= ev[j].time) {
      best = now + tau;
      partner = j;
    }
  }
  Event& e = ev_[i];
  e.time = best;
  e.partner = partner;
  e.count = partner >= 0 ? count_[partner] : 0;
  if (!hid_.empty()) heap_update(i);
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
  // Morton order: neighbours in space are neighbours in memory.
  const double cell = std::max(2.0 * class_rho_[0] * std::max(s0_, 0.05),
                               std::min({box_.length.x, box_.length.y, box_.length.z}) * 1e-4);
  std::vector<Vec3> pos(body_.size());
  for (std::size_t i = 0; i < body_.size(); ++i) pos[i] = body_[i].x;
  const std::vector<int> order = spatial_order(box_, pos, cell);
  {
    std::vector<Body> b2(body_.size());
    std::vector<int> c2(body_.size()), id2(body_.size());
    std::vector<std::uint32_t> n2(body_.size());
    // spatial_order's keys (8 B) and stable-sort buffer (up to 4 B) per particle are gone by
    // now; counted all the same, as they were alive beside everything else.
    note_memory(body_.size() *
                (sizeof(Vec3) + sizeof(int) + 12 + sizeof(Body) + 2 * sizeof(int) + sizeof(std::uint32_t)));
    for (std::size_t k = 0; k < order.size(); ++k) {
      b2[k] = body_[order[k]];
      c2[k] = cls_[order[k]];
      id2[k] = id_[order[k]];
      n2[k] = count_[order[k]];
    }
    body_.swap(b2);
    cls_.swap(c2);
    id_.swap(id2);
    count_.swap(n2);
  }
  build_grids();
  build_lists();
  hid_.clear();
  for (auto& e : ev_) e = Event{inf, -2, 0};
  for (int i = 0; i < static_cast<int>(body_.size()); ++i) predict(i);
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
    if (e.time >= t_end_) {
      reached_end = std::isfinite(t_end_);
      if (reached_end) now = t_end_;
      break;
    }
    now = e.time;
    Body& bi = bodies[i];
    if (e.partner >= 0) {
      const int j = e.partner;
      if (count_[j] != e.count) {  // partner changed velocity since: predict again
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
      const double sig1 = bi.rho + bj.rho;
      const double u = dot(bj.v - bi.v, nrm);
      virial_ += std::abs(u) * r;  // exchanged momentum (unit masses) times distance, growth part excluded
      collide(bi.v, bj.v, nrm, sig1 * g, boost);
      ++count_[i];
      ++count_[j];
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
    double fill = 0.0;
    for (int x : list_fill_) fill += x;
    fill /= static_cast<double>(n);
    if (t > 0.5 * c && fill < 12.0)
      skin_rel_ = std::min(2.0, skin_rel_ * 1.5);
    else if (t < 0.1 * c || fill > 20.0)
      skin_rel_ = std::max(0.005, skin_rel_ * 0.8);
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
