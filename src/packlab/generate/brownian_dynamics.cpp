#include "packlab/generate/brownian_dynamics.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/io/options.hpp"

namespace packlab::generate {

namespace {

// Neighbour-list skin [a]. The list only decides which pairs are examined: a pair unlisted at
// the build was at least 2a + cutoff + skin apart, and the list is rebuilt before two spheres
// can have closed that gap by the skin (2 max displacement >= skin, NeighborList::needs_rebuild),
// so every pair within the cut-off is listed at any skin. A larger skin lists more pairs beyond
// the cut-off and rebuilds less often: 0.3 a (rebuilt about every 60 steps at the default step,
// 0.1 a every ~8) was the fastest of 0.1 ... 0.5 a (docs/bd.md). A different skin changes the
// result only by rounding (positions are wrapped into the box at other steps). A checkpoint
// keeps the skin its list was built with.
constexpr double list_skin = 0.3;

// Spheres per chunk of the pair loop (dynamic schedule: the thread that draws the normals
// takes fewer); a pair's force goes to its own slot, so the chunking changes no result.
constexpr int pair_chunk = 64;

}  // namespace

void BdParams::validate() const {
  BdParams copy = *this;
  io::ConfigSchema declared("generate bd");
  io::add_bd_params(declared, copy);
  declared.validate();
  const double lambda = screening_length();
  require(cutoff > 2.0 * min_separation, "cutoff", cutoff,
          fmt::format("> 2 min_separation = {:g} m", 2 * min_separation));
  require(bond_separation > 0.0 && bond_separation < cutoff, "bond_separation", bond_separation,
          fmt::format("in (0, cutoff = {:g} m)", cutoff));
  require(std::isfinite(lambda) && lambda > 0.0, "debye_length", lambda, "> 0 m");
  require(!(central_bonds && bond_slip_force > 0.0), "bond_slip_force", bond_slip_force,
          "0 with central_bonds (a central bond resists no tangential force)");
  // A periodic image may interact with a sphere only once: bonds use the minimum image.
  const double range = 2.0 * radius + cutoff;
  require(box_edge() > 2.0 * range, "particles", static_cast<double>(particles),
          fmt::format("enough for a box edge > 2 (2 radius + cutoff) = {:g} m (edge {:g} m)", 2.0 * range, box_edge()));
  const double phi0 = volume_fraction * std::pow(1.0 + 0.5 * initial_separation / radius, 3);
  require(phi0 <= 0.62, "initial_separation", initial_separation,
          fmt::format("small enough that the inflated start packs (volume fraction {:.3f} > 0.62)", phi0));
}

double BdParams::diffusion_coefficient() const { return kT() / (6.0 * std::numbers::pi * viscosity * radius); }
double BdParams::diffusion_time() const { return radius * radius / diffusion_coefficient(); }
double BdParams::screening_length() const {
  return ionic_strength > 0.0 ? debye_length_from_ionic_strength(ionic_strength, relative_permittivity, temperature)
                              : debye_length;
}
double BdParams::step() const {
  if (time_step > 0.0) return time_step;
  const double rms = step_fraction * screening_length();
  return rms * rms / (2.0 * diffusion_coefficient());
}
dem::Dlvo::Params BdParams::dlvo() const {
  return {0.0,
          hamaker_constant,
          surface_potential,
          surface_potential,
          screening_length(),
          relative_permittivity,
          min_separation,
          cutoff};
}
double BdParams::box_edge() const {
  return radius * std::cbrt(4.0 * std::numbers::pi * static_cast<double>(particles) / (3.0 * volume_fraction));
}

double debye_length_from_ionic_strength(double ionic_strength, double relative_permittivity, double temperature) {
  return std::sqrt(relative_permittivity * dem::Dlvo::vacuum_permittivity * boltzmann_constant * temperature /
                   (2.0 * avogadro_constant * elementary_charge * elementary_charge * ionic_strength));
}

DlvoProfile dlvo_profile(const dem::Dlvo::Params& p, double radius, double kT) {
  DlvoProfile out;
  const auto u = [&](double h) { return dem::Dlvo::potential(p, radius, radius, h).energy / kT; };
  const auto f = [&](double h) { return dem::Dlvo::potential(p, radius, radius, h).force; };
  out.cutoff_kT = u(p.cutoff);
  // Log-spaced grid from h_min to the cut-off.
  const int n = 4000;
  const double ratio = std::pow(p.cutoff / p.min_separation, 1.0 / (n - 1));
  std::vector<double> h(n), v(n);
  for (int k = 0; k < n; ++k) {
    h[k] = p.min_separation * std::pow(ratio, k);
    v[k] = u(h[k]);
  }
  // Root of the force between a and b (sign change), by bisection.
  const auto root = [&](double a, double b) {
    const double fa = f(a);
    for (int it = 0; it < 200 && b - a > 1e-15 * b; ++it) {
      const double m = 0.5 * (a + b);
      if ((f(m) > 0.0) == (fa > 0.0))
        a = m;
      else
        b = m;
    }
    return 0.5 * (a + b);
  };
  int kmax = -1;
  for (int k = 1; k + 1 < n; ++k)
    if (v[k] >= v[k - 1] && v[k] > v[k + 1]) {
      kmax = k;
      break;
    }
  if (kmax < 0) return out;
  out.has_barrier = true;
  out.barrier_separation = root(h[kmax - 1], h[kmax + 1]);
  out.barrier_kT = u(out.barrier_separation);
  int kmin = -1;
  for (int k = kmax + 1; k + 1 < n; ++k)
    if (v[k] <= v[k - 1] && v[k] < v[k + 1]) {
      kmin = k;
      break;
    }
  if (kmin < 0) {  // still falling at the cut-off
    out.secondary_separation = p.cutoff;
    out.secondary_kT = out.cutoff_kT;
  } else {
    out.secondary_separation = root(h[kmin - 1], h[kmin + 1]);
    out.secondary_kT = u(out.secondary_separation);
  }
  out.barrier_above_secondary_kT = out.barrier_kT - out.secondary_kT;
  return out;
}

// ---- BdRun ----

void BdRun::setup() {
  params_.validate();
  const long n = params_.particles;
  const double a = params_.radius;
  const double edge = params_.box_edge();
  box_ = Box{};
  box_.length = {edge, edge, edge};
  box_.periodic = {true, true, true};
  law_ = params_.dlvo();
  dt_ = params_.step();
  const double drag = 6.0 * std::numbers::pi * params_.viscosity * a;
  mobility_ = 1.0 / drag;
  noise_ = std::sqrt(2.0 * params_.diffusion_coefficient() * dt_);
  max_drift_ = noise_;
  bond_k_ = params_.bond_stiffness_factor * drag / dt_;
  law_.normal_stiffness = bond_k_;
  bond_length_ = 2.0 * a + params_.bond_separation;
  reach2_ = (2.0 * a + params_.cutoff) * (2.0 * a + params_.cutoff);
  const double tau = params_.diffusion_time();
  max_steps_ = std::max(1L, static_cast<long>(std::ceil(params_.duration * tau / dt_ - 1e-9)));
  require(max_steps_ <= 1'000'000'000'000L, "duration", params_.duration,
          fmt::format("<= 1e12 steps of {:g} s (this is {:g} steps)", dt_, params_.duration * tau / dt_));
  sample_every_ = std::max(1L, max_steps_ / std::max(1L, params_.samples));
  window_steps_ = std::max(1L, static_cast<long>(std::llround(params_.stable_window * tau / dt_)));
  radius_.assign(static_cast<std::size_t>(n), a);
  normals_.assign(static_cast<std::size_t>(n), Vec3{});
  force_.assign(static_cast<std::size_t>(n), Vec3{});
  // Every sphere can hold max_bonds_per_sphere bonds: room for all of them, allocated once.
  const std::size_t bond_room = static_cast<std::size_t>(n) * max_bonds_per_sphere / 2;
  bonds_.reserve(bond_room);
  bond_force_.reserve(bond_room);
  new_bonds_.reserve(bond_room);
  // The threads share that room (a thread finding more in one step grows its buffer once).
  const std::size_t threads = static_cast<std::size_t>(std::max(1, params_.threads));
  thread_new_bonds_.assign(threads, {});
  for (auto& found : thread_new_bonds_) found.reserve(bond_room / threads + 1);
  sphere_bonds_.assign(static_cast<std::size_t>(n), {});
  parent_.resize(static_cast<std::size_t>(n));
  size_.resize(static_cast<std::size_t>(n));
  list_.set_skin(list_skin * a);
  list_.set_reach(params_.cutoff);
}

BdRun::BdRun(const BdParams& params, Random rng) : params_(params), rng_(std::move(rng)) {
  setup();
  const long n = params_.particles;
  const double a = params_.radius;
  // Start: force-biased packing of spheres inflated by h_0 / 2 (no gap below h_0).
  const double inflated = a + 0.5 * params_.initial_separation;
  FbaParams fp;
  fp.target_porosity = 1.0 - params_.volume_fraction * std::pow(inflated / a, 3);
  fp.tolerance = 1e-4;
  fp.threads = params_.threads;
  const std::vector<double> rho(static_cast<std::size_t>(n), 1.0);
  const FbaResult start = fba_pack(box_, rho, fp, rng_);
  if (start.status.stop != FbaStop::target_reached)
    fail_input(fmt::format("initial_separation = {:g} m: the start could not be packed (overlap {:.3g})",
                           params_.initial_separation, start.status.max_overlap));
  pos_ = start.packing.position;
  for (Vec3& p : pos_) p = box_.wrap(p);
  start_ = pos_;
  wraps_.assign(static_cast<std::size_t>(n), {0, 0, 0});
  partners_.assign(static_cast<std::size_t>(n), {});
  partner_count_.assign(static_cast<std::size_t>(n), 0);
  index_bonds();
  status_ = measure();
  log_.push_back(status_);
}

bool BdRun::bonded(int i, int j) const {
  const auto& p = partners_[static_cast<std::size_t>(i)];
  const int c = partner_count_[static_cast<std::size_t>(i)];
  for (int k = 0; k < c; ++k)
    if (p[static_cast<std::size_t>(k)] == j) return true;
  return false;
}

void BdRun::add_bond(int i, int j, const Vec3& d) {
  for (const int s : {i, j}) {
    int& c = partner_count_[static_cast<std::size_t>(s)];
    if (c >= max_bonds_per_sphere)
      throw std::logic_error(fmt::format("brownian dynamics: sphere {} has {} bonds", s, c));
    sphere_bonds_[static_cast<std::size_t>(s)][static_cast<std::size_t>(c)] = static_cast<int>(bonds_.size());
    partners_[static_cast<std::size_t>(s)][static_cast<std::size_t>(c++)] = s == i ? j : i;
  }
  bonds_.push_back({i, j, d * (bond_length_ / norm(d))});
}

void BdRun::index_bonds() {
  // A sphere's partners_ slots were filled in bond order: its k-th slot is its k-th bond.
  const std::size_t n = pos_.size();
  std::vector<int> count(n, 0);
  for (std::size_t b = 0; b < bonds_.size(); ++b)
    for (const int s : {bonds_[b].i, bonds_[b].j}) {
      if (s < 0 || static_cast<std::size_t>(s) >= n || count[static_cast<std::size_t>(s)] >= max_bonds_per_sphere)
        fail_input("checkpoint is damaged: brownian dynamics bonds do not match the spheres");
      const int c = count[static_cast<std::size_t>(s)]++;
      if (partners_[static_cast<std::size_t>(s)][static_cast<std::size_t>(c)] !=
          (s == bonds_[b].i ? bonds_[b].j : bonds_[b].i))
        fail_input("checkpoint is damaged: brownian dynamics bonds do not match the bond partners");
      sphere_bonds_[static_cast<std::size_t>(s)][static_cast<std::size_t>(c)] = static_cast<int>(b);
    }
  for (std::size_t s = 0; s < n; ++s)
    if (count[s] != partner_count_[s])
      fail_input("checkpoint is damaged: brownian dynamics bond counts do not match the bonds");
}

void BdRun::index_pairs() {
  // Counting sort of the listed pairs by partner, in list order: incoming_first_[j + 1] ends
  // up as the end of j's range (the start of j + 1's).
  const int n = static_cast<int>(pos_.size());
  const std::vector<int>& partner = list_.partner();
  incoming_first_.assign(static_cast<std::size_t>(n) + 2, 0);
  for (int i = 0; i < n; ++i)
    for (int k = list_.first(i); k < list_.first(i + 1); ++k)
      if (partner[static_cast<std::size_t>(k)] != i)
        ++incoming_first_[static_cast<std::size_t>(partner[static_cast<std::size_t>(k)]) + 2];
  for (int j = 0; j < n; ++j)
    incoming_first_[static_cast<std::size_t>(j) + 2] += incoming_first_[static_cast<std::size_t>(j) + 1];
  incoming_.resize(static_cast<std::size_t>(incoming_first_[static_cast<std::size_t>(n) + 1]));
  for (int i = 0; i < n; ++i)
    for (int k = list_.first(i); k < list_.first(i + 1); ++k) {
      const int j = partner[static_cast<std::size_t>(k)];
      if (j != i) incoming_[static_cast<std::size_t>(incoming_first_[static_cast<std::size_t>(j) + 1]++)] = k;
    }
  incoming_first_.pop_back();
  pair_force_.resize(partner.size());
  indexed_builds_ = list_.builds();
}

// Threads and the order of sums. One thread runs the serial loop: over the listed pairs, then
// the bonds, each adding its force to both spheres. Several threads give every listed pair's
// force its own slot (pairs of sphere i by whichever thread takes i's chunk) and every bond's
// its own; after one barrier each sphere adds its slots in the serial loop's order: the pairs
// where it is the partner (their owner i < it: earlier in the list) in list order, then its own
// in list order, then its bonds in bond order. Every force is then the same sum in the same
// order at any thread count. A pair that does not act (beyond the cut-off, bonded, its own
// image) gives +0: adding it can only turn a -0 component into +0, which no position sees
// (x + drift + noise xi with drift = ±0). New bonds are collected per thread, put in list order
// (the serial loop's) and added after the update: they act from the next step on.
void BdRun::step(bool brownian) {
  const int n = static_cast<int>(pos_.size());
  if (!built_ || list_.needs_rebuild(pos_, radius_)) {
    list_.build(box_, pos_, radius_, params_.threads, &wraps_);
    built_ = true;
  }
  const int threads = static_cast<int>(thread_new_bonds_.size());
  if (threads > 1 && indexed_builds_ != list_.builds()) index_pairs();
  const double a = params_.radius;
  const double bond_below = 2.0 * a + params_.bond_separation;
  const bool central = params_.central_bonds;
  const int bond_count = static_cast<int>(bonds_.size());
  // Plain local pointers: inside the parallel region members would be reloaded through `this`.
  const int* __restrict first = list_.first_pairs().data();
  const int* __restrict partner = list_.partner().data();
  const std::uint8_t* __restrict image = list_.image().data();
  Vec3* __restrict pos = pos_.data();
  Vec3* __restrict normals = normals_.data();
  Bond* __restrict bonds = bonds_.data();  // slip bonds move their rest direction (each by its own iteration)
  const double reach2 = reach2_;
  const dem::Dlvo::Params law = law_;
  std::array<Vec3, 27> offset;
  for (int c = 0; c < 27; ++c) offset[static_cast<std::size_t>(c)] = list_.image_offset(c);

  // The normals from the one generator in sphere order. One normal_distribution per step,
  // discarded at its end: no state outside rng_ between steps.
  const auto draw_normals = [&] {
    if (!brownian) return;
    std::normal_distribution<double> normal(0.0, 1.0);
    for (int i = 0; i < n; ++i) {
      normals[i].x = normal(rng_.engine());
      normals[i].y = normal(rng_.engine());
      normals[i].z = normal(rng_.engine());
    }
  };
  // Listed pair k of sphere i: the DLVO force on its partner when unbonded and within the
  // cut-off, else +0; a pair closer than bond_separation is recorded as a new bond.
  const auto pair_force = [&](int i, const Vec3& xi, int k, std::vector<NewBond>& found) {
    const int j = partner[k];
    if (j == i) return Vec3{};  // its own image: the box is larger than twice the range
    const Vec3 d = pos[j] + offset[image[k]] - xi;
    const double r2 = norm2(d);
    if (r2 >= reach2 || bonded(i, j)) return Vec3{};
    const double r = std::sqrt(r2);
    if (r < bond_below) found.push_back({k, {i, j, d}});
    const double fn = dem::Dlvo::interaction_force(law, a, a, r - 2.0 * a);
    return (fn / r) * d;
  };
  // Bond b: F_j = -k_b (d - d_0) (central: along d only). A slip bond first turns d_0 towards d
  // when its tangential force k_b |d_0 - (d_0 . n) n| exceeds F_s: the new d_0 keeps its length
  // and has the tangential part F_s / k_b on the side it had (the slider's return mapping).
  const double slip_offset = params_.bond_slip_force > 0.0 ? params_.bond_slip_force / bond_k_ : 0.0;
  const auto bond_force = [&](int b) {
    const Vec3 d = box_.minimum_image(pos[bonds[b].j] - pos[bonds[b].i]);
    if (central) {
      const double r = norm(d);
      return (-bond_k_ * (r - bond_length_) / r) * d;
    }
    if (slip_offset > 0.0) bonds[b].rest = slip_bond_rest(bonds[b].rest, d, bond_length_, slip_offset);
    return -bond_k_ * (d - bonds[b].rest);
  };
  // Ermak-McCammon step: drift (capped at the rms Brownian step) + Brownian displacement.
  const auto advance = [&](int i, const Vec3& force) {
    Vec3 drift = (mobility_ * dt_) * force;
    const double length = norm(drift);
    if (length > max_drift_) drift *= max_drift_ / length;
    const Vec3 xi = brownian ? normals[i] : Vec3{};
    pos[i] += drift + noise_ * xi;
  };

  if (threads == 1) {
    std::vector<NewBond>& found = thread_new_bonds_[0];
    found.clear();
    draw_normals();
    Vec3* __restrict force = force_.data();
    std::fill(force_.begin(), force_.end(), Vec3{});
    for (int i = 0; i < n; ++i) {
      const Vec3 xi = pos[i];
      for (int k = first[i]; k < first[i + 1]; ++k) {
        const Vec3 f = pair_force(i, xi, k, found);
        force[partner[k]] += f;
        force[i] -= f;
      }
    }
    for (int b = 0; b < bond_count; ++b) {
      const Vec3 f = bond_force(b);
      force[bonds[b].j] += f;
      force[bonds[b].i] -= f;
    }
    for (int i = 0; i < n; ++i) advance(i, force[i]);
  } else {
    bond_force_.resize(bonds_.size());  // within the room reserved at setup
    const int* __restrict incoming_first = incoming_first_.data();
    const int* __restrict incoming = incoming_.data();
    const int* __restrict bond_count_of = partner_count_.data();
    const auto* __restrict bonds_of = sphere_bonds_.data();
    Vec3* __restrict pair_slot = pair_force_.data();
    Vec3* __restrict bond_slot = bond_force_.data();
#pragma omp parallel num_threads(threads)
    {
      std::vector<NewBond>& found = thread_new_bonds_[static_cast<std::size_t>(omp_get_thread_num())];
      found.clear();
      // One thread draws the normals while the others start on the pairs.
#pragma omp single nowait
      draw_normals();
#pragma omp for schedule(dynamic, pair_chunk) nowait
      for (int i = 0; i < n; ++i) {
        const Vec3 xi = pos[i];
        for (int k = first[i]; k < first[i + 1]; ++k) pair_slot[k] = pair_force(i, xi, k, found);
      }
#pragma omp for schedule(dynamic, 256)
      for (int b = 0; b < bond_count; ++b) bond_slot[b] = bond_force(b);
        // (the barrier above: every slot and the normals are written)
#pragma omp for schedule(dynamic, 256) nowait
      for (int i = 0; i < n; ++i) {
        Vec3 force{};
        for (int m = incoming_first[i]; m < incoming_first[i + 1]; ++m) force += pair_slot[incoming[m]];
        for (int k = first[i]; k < first[i + 1]; ++k) force -= pair_slot[k];
        for (int c = 0; c < bond_count_of[i]; ++c) {
          const int b = bonds_of[i][static_cast<std::size_t>(c)];
          if (bonds[b].j == i)
            force += bond_slot[b];
          else
            force -= bond_slot[b];
        }
        advance(i, force);
      }
    }
  }
  new_bonds_.clear();
  for (const auto& found : thread_new_bonds_) new_bonds_.insert(new_bonds_.end(), found.begin(), found.end());
  if (!new_bonds_.empty()) {
    std::sort(new_bonds_.begin(), new_bonds_.end(), [](const NewBond& x, const NewBond& y) { return x.pair < y.pair; });
    for (const NewBond& b : new_bonds_)
      if (!bonded(b.bond.i, b.bond.j)) add_bond(b.bond.i, b.bond.j, b.bond.rest);
  }
  if (brownian) ++step_;
}

Vec3 slip_bond_rest(const Vec3& rest, const Vec3& d, double rest_length, double max_offset) {
  const Vec3 n = (1.0 / norm(d)) * d;
  const Vec3 tangential = rest - dot(rest, n) * n;
  const double offset = norm(tangential);
  if (offset <= max_offset) return rest;
  const double sine = std::min(1.0, max_offset / rest_length);
  return rest_length * (std::sqrt(1.0 - sine * sine) * n + (sine / offset) * tangential);
}

BdStatus BdRun::measure() const {
  BdStatus s;
  s.step = step_;
  s.time = static_cast<double>(step_) * dt_;
  s.reduced_time = s.time / params_.diffusion_time();
  s.bonds = static_cast<long>(bonds_.size());
  s.seconds = seconds_;
  // Clusters: union-find over the bonds.
  const std::size_t n = pos_.size();
  for (std::size_t i = 0; i < n; ++i) {
    parent_[i] = static_cast<int>(i);
    size_[i] = 1;
  }
  const auto find = [&](int x) {
    while (parent_[static_cast<std::size_t>(x)] != x) {
      parent_[static_cast<std::size_t>(x)] = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(x)])];
      x = parent_[static_cast<std::size_t>(x)];
    }
    return x;
  };
  for (const Bond& b : bonds_) {
    int x = find(b.i), y = find(b.j);
    if (x == y) continue;
    if (size_[static_cast<std::size_t>(x)] < size_[static_cast<std::size_t>(y)]) std::swap(x, y);
    parent_[static_cast<std::size_t>(y)] = x;
    size_[static_cast<std::size_t>(x)] += size_[static_cast<std::size_t>(y)];
  }
  double msd = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (find(static_cast<int>(i)) == static_cast<int>(i)) {
      ++s.clusters;
      s.largest_cluster = std::max(s.largest_cluster, static_cast<long>(size_[i]));
    }
    const Vec3 unwrapped = pos_[i] + box_.shift_vector(wraps_[i]);
    msd += norm2(unwrapped - start_[i]);
  }
  s.msd = msd / static_cast<double>(n);
  return s;
}

void BdRun::record() {
  status_ = measure();
  log_.push_back(status_);
}

bool BdRun::run(long steps, const std::function<void(const BdStatus&)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const double seconds_before = seconds_;
  const auto elapsed = [&] {
    return seconds_before + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  long done = 0;
  while (!finished_ && (steps < 0 || done < steps)) {
    step();
    ++done;
    const bool last = step_ >= max_steps_;
    const bool window_end = params_.until_stable && step_ % window_steps_ == 0;
    if (step_ % sample_every_ == 0 || last || window_end) {
      seconds_ = elapsed();
      record();
      if (progress) progress(status_);
    }
    if (window_end) {
      const long now = static_cast<long>(bonds_.size());
      if (step_ > window_steps_ && static_cast<double>(now - window_bonds_) <=
                                       params_.stable_tolerance * static_cast<double>(std::max(now, 1L))) {
        stable_ = true;
        finished_ = true;
      }
      window_bonds_ = now;
    }
    if (last) finished_ = true;
    if (finished_) {
      for (long k = 0; k < params_.quench_steps; ++k) step(false);
      status_ = measure();  // the quenched structure (no log row: time did not advance)
      if (progress) progress(status_);
    }
  }
  seconds_ = elapsed();
  return finished_;
}

BdResult BdRun::result() const {
  BdResult r;
  r.status = measure();
  r.status.seconds = seconds_;
  r.stable = stable_;
  r.log = log_;
  r.time_step = dt_;
  r.bond_stiffness = bond_k_;
  const std::size_t n = pos_.size();
  r.mean_coordination = 2.0 * static_cast<double>(bonds_.size()) / static_cast<double>(n);
  Packing& p = r.packing;
  p.box = box_;
  for (std::size_t i = 0; i < n; ++i) p.add(box_.wrap(pos_[i]), radius_[i]);
  for (const Bond& b : bonds_) {
    // Image of j bonded to i in the wrapped positions: r_j + image L - r_i = the bond vector.
    const Vec3 d = p.position[static_cast<std::size_t>(b.j)] - p.position[static_cast<std::size_t>(b.i)];
    p.bonds.i.push_back(b.i);
    p.bonds.j.push_back(b.j);
    p.bonds.image.push_back(box_.image_shift(d));
    p.bonds.material.push_back(0);
    p.bonds.rest_length.push_back(bond_length_);
    p.bonds.state.push_back(0);
  }
  return r;
}

// ---- checkpoints ----

namespace {
constexpr std::uint64_t bd_state_version = 2;  // 2: bond_slip_force
}

void BdRun::save_state(std::ostream& out) const {
  binary::write(out, bd_state_version);
  binary::write(out, params_);
  binary::write_random(out, rng_);
  binary::write_vector(out, pos_);
  binary::write_vector(out, start_);
  binary::write_vector(out, wraps_);
  binary::write_vector(out, bonds_);
  binary::write_vector(out, partners_);
  binary::write_vector(out, partner_count_);
  binary::write(out, step_);
  binary::write(out, window_bonds_);
  binary::write(out, finished_);
  binary::write(out, stable_);
  binary::write(out, status_);
  binary::write_vector(out, log_);
  binary::write(out, seconds_);
  binary::write(out, built_);
  if (built_) list_.save(out);
}

BdRun BdRun::load_state(std::istream& in, int threads) {
  BdRun r;
  std::uint64_t version = 0;
  binary::read(in, version, "brownian dynamics state version");
  if (version != bd_state_version)
    fail_input(fmt::format("checkpoint: brownian dynamics state version {} (this packlab writes {})", version,
                           bd_state_version));
  binary::read(in, r.params_, "brownian dynamics parameters");
  if (threads > 0) r.params_.threads = threads;
  r.setup();
  binary::read_random(in, r.rng_);
  binary::read_vector(in, r.pos_, "positions");
  binary::read_vector(in, r.start_, "start positions");
  binary::read_vector(in, r.wraps_, "wraps");
  binary::read_vector(in, r.bonds_, "bonds");
  binary::read_vector(in, r.partners_, "bond partners");
  binary::read_vector(in, r.partner_count_, "bond counts");
  const std::size_t n = static_cast<std::size_t>(r.params_.particles);
  if (r.pos_.size() != n || r.start_.size() != n || r.wraps_.size() != n || r.partners_.size() != n ||
      r.partner_count_.size() != n)
    fail_input("checkpoint is damaged: brownian dynamics arrays do not match the particle count");
  binary::read(in, r.step_, "step");
  binary::read(in, r.window_bonds_, "window bonds");
  binary::read(in, r.finished_, "finished");
  binary::read(in, r.stable_, "stable");
  binary::read(in, r.status_, "status");
  binary::read_vector(in, r.log_, "log");
  binary::read(in, r.seconds_, "seconds");
  binary::read(in, r.built_, "list built");
  if (r.built_) r.list_.load(in);
  r.index_bonds();
  return r;
}

BdResult brownian_dynamics(const BdParams& params, std::uint64_t seed,
                           const std::function<void(const BdStatus&)>& progress) {
  BdRun run(params, Random(seed));
  run.run(-1, progress);
  return run.result();
}

}  // namespace packlab::generate
