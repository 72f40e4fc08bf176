// One time step: the contact law over the listed pairs, the bond law over the bonds and the
// walls, then the leap-frog integration with local damping and the refreshed time step.
// Everything in the loop is templated on the laws (dem/contact/, dem/bond/), so each law gets
// its own inlined loop and adding one touches nothing here.
//
// Threads and the order of sums. Each thread owns a contiguous range of particles (sorted
// along a space-filling curve) with the listed pairs and bonds whose first particle is in it
// (partition_work). A pair (i, j) has j >= i, so a particle receives contributions only from
// pairs and bonds owned by itself or by earlier ranges. Those that reach a particle of a
// later range ("crossing") are evaluated first, the pairs shared out evenly among all threads,
// and kept; after one barrier each thread adds the crossing contributions of earlier threads
// to its particles and then its own, in pair order. Every particle's force is then the same
// sum in the same order as with one thread: the result does not depend on the thread count,
// no thread writes another's particles, and there is no whole-size buffer to clear or reduce.
//
// The contact law runs over blocks of 30 listed pairs into per-component arrays (PairBlock):
// no branch on whether a pair touches (its result is masked), so the loop vectorizes; the
// forces are then added to the particles in a short scalar loop. packlab is compiled without
// fused multiply-add contraction (-ffp-contract=off, CMakeLists.txt): a pair's force must not depend on whether it
// falls in the vector body or the scalar remainder of that loop, which differ in where the compiler fuses
// multiply-adds, and a pair's place in a block depends on the thread count.
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cmath>
#include <limits>
#include <new>
#include <string>

#include "packlab/core/error.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/dem/local_damping.hpp"

namespace packlab::dem {

namespace {

// Particles per chunk of the sums over all particles (energies, wall forces): fixed, so the
// sums are the same at any thread count.
constexpr int chunk_size = 4096;

int chunk_count(int n) { return (n + chunk_size - 1) / chunk_size; }

// What a bond counts, in listed pairs, when the threads' shares of work are cut (the bonded
// compression benchmark balanced no better at 4, 8 or 16).
constexpr long bond_work = 2;

}  // namespace

void Engine::partition_work() {
  const int n = static_cast<int>(particles_.size());
  const int T = threads_;
  const auto& first = neighbors_.first_pairs();
  const auto& partner = neighbors_.partner();
  // A listed pair counts 1, a bond 2 (its law does more).
  const bool any_bonds = !bond_first_.empty();
  auto work_before = [&](int i) { return static_cast<long>(first[i]) + (any_bonds ? bond_work * bond_first_[i] : 0L); };
  const long total = work_before(n);
  // Never shrunk: switching between one thread and more (adapt_threads) keeps every thread's
  // lists and their capacity; only the first T are used.
  if (work_.size() < static_cast<std::size_t>(T)) work_.resize(static_cast<std::size_t>(T));
  // The crossing pairs of all threads are shared out evenly before the step's barrier
  // (pair_forces), so the ranges are cut for equal work after it: equal pairs and bonds besides
  // the crossing ones. Which pairs cross depends on the cuts, so the cuts are found twice: first
  // for equal work in all, then for equal work besides what crosses those first cuts (at 2
  // threads 17 % of the first range's pairs cross in the relax benchmark).
  std::vector<int>& first_cut = partition_first_cut_;
  first_cut.assign(static_cast<std::size_t>(T), n);
  for (int t = 0, i = 0; t + 1 < T; ++t) {
    const long target = total * (t + 1) / T;
    while (i < n && work_before(i) < target) ++i;
    first_cut[static_cast<std::size_t>(t)] = i;
  }
  // Work of particle k after the barrier under the first cuts, in half pairs: a pair 2, a
  // crossing pair 1 (it is still walked, and its kept result added), a bond 4.
  auto own_work = [&](int k, int range_end) {
    long w = 0;
    for (int p = first[k]; p < first[k + 1]; ++p) w += 1 + (partner[p] < range_end);
    if (any_bonds)
      for (int b = bond_first_[k]; b < bond_first_[k + 1]; ++b)
        w += 2 * bond_work * (std::max(bonds_.i[b], bonds_.j[b]) < range_end);
    return w;
  };
  long own_total = 0;
  for (int t = 0, k = 0; t < T; ++t)
    for (; k < first_cut[static_cast<std::size_t>(t)]; ++k)
      own_total += own_work(k, first_cut[static_cast<std::size_t>(t)]);
  int i = 0;
  long own_before = 0;
  int first_range = 0;  // the first cut's range of particle i
  for (int t = 0; t < T; ++t) {
    ThreadWork& w = work_[static_cast<std::size_t>(t)];
    w.particle_begin = i;
    const long target = own_total * (t + 1) / T;
    if (t + 1 == T)
      i = n;
    else
      while (i < n && own_before < target) {
        while (i >= first_cut[static_cast<std::size_t>(first_range)]) ++first_range;
        own_before += own_work(i, first_cut[static_cast<std::size_t>(first_range)]);
        ++i;
      }
    w.particle_end = i;
    w.crossing_bonds.clear();
    w.crossing_bond_results.clear();
    if (!any_bonds) continue;
    for (int b = bond_first_[w.particle_begin]; b < bond_first_[w.particle_end]; ++b)
      if (std::max(bonds_.i[b], bonds_.j[b]) >= w.particle_end) w.crossing_bonds.push_back(b);
    w.crossing_bond_results.resize(w.crossing_bonds.size());
    w.broken_crossing_bonds.reserve(w.crossing_bonds.size());
    // A bond breaks at most once per step and each is evaluated by one thread: with room for
    // all of this range's bonds, recording a break never allocates, so nothing in the step's
    // parallel region can throw (an exception there, between barriers, would abort).
    w.failed_bonds.reserve(static_cast<std::size_t>(bond_first_[w.particle_end] - bond_first_[w.particle_begin]));
  }
  // The near list follows the new ranges (and the new list) at the next step; until then the
  // threads walk every listed pair.
  near_active_ = false;
  near_stale_ = true;
  collect_crossing_pairs();
}

void Engine::collect_crossing_pairs() {
  const int T = threads_;
  const auto& first = neighbors_.first_pairs();
  const auto& partner = neighbors_.partner();
  for (int t = 0; t < T; ++t) {
    ThreadWork& w = work_[static_cast<std::size_t>(t)];
    w.crossing_pairs.clear();
    w.crossing_pair_owners.clear();
    if (near_active_) {
      for (std::size_t k = 0; k < w.near_pairs.size(); ++k)
        if (partner[static_cast<std::size_t>(w.near_pairs[k])] >= w.particle_end) {
          w.crossing_pairs.push_back(w.near_pairs[k]);
          w.crossing_pair_owners.push_back(w.near_owners[k]);
        }
    } else {
      for (int owner = w.particle_begin; owner < w.particle_end; ++owner)
        for (int p = first[owner]; p < first[owner + 1]; ++p)
          if (partner[p] >= w.particle_end) {
            w.crossing_pairs.push_back(p);
            w.crossing_pair_owners.push_back(owner);
          }
    }
    w.crossing_pair_results.resize(w.crossing_pairs.size());
    w.crossing_pair_acts.resize(w.crossing_pairs.size());
  }
  // Each thread's slice of the crossing pairs of all threads, concatenated in thread order,
  // evaluated before the step's barrier (pair_forces): about the same work for every thread,
  // its own crossing bonds counted.
  long crossing_total = 0, crossing_bond_work = 0;
  for (int t = 0; t < T; ++t) {
    crossing_total += static_cast<long>(work_[static_cast<std::size_t>(t)].crossing_pairs.size());
    crossing_bond_work += bond_work * static_cast<long>(work_[static_cast<std::size_t>(t)].crossing_bonds.size());
  }
  const long share = (crossing_total + crossing_bond_work) / T;
  long slice_begin = 0;
  for (int t = 0; t < T; ++t) {
    ThreadWork& w = work_[static_cast<std::size_t>(t)];
    const long own_bonds = bond_work * static_cast<long>(w.crossing_bonds.size());
    const long slice_end =
        t + 1 == T ? crossing_total : std::min(crossing_total, slice_begin + std::max(0L, share - own_bonds));
    w.crossing_slice_begin = slice_begin;
    w.crossing_slice_end = slice_end;
    slice_begin = slice_end;
  }
}

// The listed pairs of one block that act (touch, or are within the law's reach, and are not
// held by a bond), compacted, with what the law reads about them in one array per quantity,
// and the law's results in the same form. Filled by gather_pairs, evaluated by contact_block
// in a loop that vectorizes (contiguous loads, no branch), added to the particles in order.
template <class Law>
struct PairBlock {
  static constexpr int capacity = 30;
  int count = 0;
  int pair[capacity], owner[capacity], other[capacity];
  std::uint8_t evaluated_before[capacity];  // crossing pair: use the kept result
  std::uint8_t keep_history[capacity];      // per listed pair of the block
  double dx[capacity], dy[capacity], dz[capacity], distance2[capacity];
  double radius_i[capacity], radius_j[capacity], inverse_mass_i[capacity], inverse_mass_j[capacity];
  double vix[capacity], viy[capacity], viz[capacity], vjx[capacity], vjy[capacity], vjz[capacity];
  double wix[capacity], wiy[capacity], wiz[capacity], wjx[capacity], wjy[capacity], wjz[capacity];
  typename Law::History history[capacity];
  typename Law::Params params[capacity];
  double force_x[capacity], force_y[capacity], force_z[capacity];
  double torque_i_x[capacity], torque_i_y[capacity], torque_i_z[capacity];
  double torque_j_x[capacity], torque_j_y[capacity], torque_j_z[capacity];
  double stiffness[capacity], stiffness_over_mass[capacity];
  double energy[capacity], force_norm[capacity], overlap[capacity];
};

// Gathers the acting pairs among `count` listed pairs (pairs[start + k] if Indirect, else
// start + k; their particles i in owners[start + k] if Indirect, else owners[k]) into the
// block, in list order, without a branch on whether a pair acts (the
// entry is written and kept only if it does). A pair out of range ends its history. Pairs
// whose j >= skip_from were evaluated before (crossing pairs): their history is left alone
// and they are listed, flagged, only if they acted, so that their kept result is added at
// their place in the order.
template <class Law, bool OneType, bool Indirect, bool Guarded, bool Central>
void Engine::gather_pairs(ContactModel<Law>& model, const int* pairs, const int* owners, int start, int count,
                          int skip_from, const std::uint8_t* crossing_acts, int& crossing_seen, PairBlock<Law>& block) {
  const Vec3* __restrict x = particles_.position.data();
  const Vec3* __restrict v = particles_.velocity.data();
  const Vec3* __restrict w = particles_.angular_velocity.data();
  const double* __restrict rad = particles_.radius.data();
  const int* __restrict type = particles_.type.data();
  const double* __restrict inverse_mass = particles_.inverse_mass.data();
  const int* __restrict owner = Indirect ? owners + start : owners;
  const int* __restrict partner = neighbors_.partner().data();
  const std::uint8_t* __restrict image = neighbors_.image().data();
  // Without bonds the flags are not kept (none is set).
  const bool any_bonded = !pair_bonded_.empty();
  const std::uint8_t* __restrict bonded = pair_bonded_.data();
  const Vec3* __restrict offsets = &neighbors_.image_offset(0);
  auto* __restrict history = model.history.data();
  const auto* __restrict params = model.pair_params.data();
  const int type_count = model.type_count;
  using History = typename Law::History;
  // Pass 1, over the listed pairs: which act, compacted (written at m, kept by m += acts).
  int m = 0;
  for (int k = 0; k < count; ++k) {
    const int p = Indirect ? pairs[start + k] : start + k;
    const int i = owner[k], j = partner[p];
    const bool before = j >= skip_from;
    // Guarded: a crossing pair's j belongs to a later thread, which may already be moving it
    // (the integration in the force region), so its state is not read. Its entry's evaluation
    // is discarded (the kept result is added) and sees a separated pair, 4 r_i along x, so
    // that it stays finite. (Unguarded this costs 2 % at one thread: a template choice.)
    const int j_read = Guarded && before ? i : j;
    const Vec3 listed = x[j_read] + offsets[image[p]] - x[i];
    const Vec3 d = Guarded && before ? Vec3{4.0 * rad[i], 0.0, 0.0} : listed;
    const double dist2 = norm2(d);
    const double ri = rad[i], rj = rad[j_read];
    const double reach = OneType ? Law::reach(params[0]) : Law::reach(params[type[i] * type_count + type[j_read]]);
    const double cutoff = ri + rj + reach;  // r_i + r_j for laws acting on overlap only
    // A crossing pair's flag is read only for crossing pairs (crossing_seen counts them).
    const bool acted_before = before && crossing_acts[before ? crossing_seen : 0];
    crossing_seen += before;
    const bool acts = (dist2 < cutoff * cutoff) & (!any_bonded || bonded[p] == 0) & !before;
    block.pair[m] = p;
    block.owner[m] = i;
    block.other[m] = j;
    block.evaluated_before[m] = before;
    block.dx[m] = d.x;
    block.dy[m] = d.y;
    block.dz[m] = d.z;
    block.distance2[m] = dist2;
    block.radius_i[m] = ri;
    block.radius_j[m] = rj;
    block.keep_history[k] = before | acts;
    m += before ? acted_before : acts;
  }
  block.count = m;
  // A pair out of range ends its history (crossing ones keep theirs); the acting ones are
  // given theirs after the evaluation. The central form keeps no history.
  if constexpr (Central) {
  } else if constexpr (!Indirect) {
    auto* __restrict h = history + start;
    for (int k = 0; k < count; ++k) h[k] = block.keep_history[k] ? h[k] : History{};
  } else {
    for (int k = 0; k < count; ++k)
      if (!block.keep_history[k]) history[pairs[start + k]] = History{};
  }
  // Pass 2, over the acting pairs: the rest of what the law reads (the central form: the
  // masses, for the time step, and the parameters alone).
  for (int c = 0; c < m; ++c) {
    const int i = block.owner[c], j = Guarded && block.evaluated_before[c] ? i : block.other[c];
    block.inverse_mass_i[c] = inverse_mass[i];
    block.inverse_mass_j[c] = inverse_mass[j];
    if constexpr (!Central) {
      block.vix[c] = v[i].x;
      block.viy[c] = v[i].y;
      block.viz[c] = v[i].z;
      block.vjx[c] = v[j].x;
      block.vjy[c] = v[j].y;
      block.vjz[c] = v[j].z;
      block.wix[c] = w[i].x;
      block.wiy[c] = w[i].y;
      block.wiz[c] = w[i].z;
      block.wjx[c] = w[j].x;
      block.wjy[c] = w[j].y;
      block.wjz[c] = w[j].z;
      block.history[c] = history[block.pair[c]];
    }
    if constexpr (!OneType) block.params[c] = params[type[i] * type_count + type[j]];
  }
  if constexpr (OneType) block.params[0] = params[0];
}

// The contact law over the gathered pairs: contiguous loads, the law inlined, selects instead
// of branches, so the loop vectorizes. Writes the new histories back (the central form has none).
template <class Law, bool OneType, bool Measure, bool Central>
void Engine::contact_block(ContactModel<Law>& model, PairBlock<Law>& block) {
  const int count = block.count;
  const double dt = dt_;
  auto* __restrict history = model.history.data();
  typename Law::History updated[PairBlock<Law>::capacity];
#pragma GCC ivdep
  for (int c = 0; c < count; ++c) {
    const typename Law::Params pair_params = block.params[OneType ? 0 : c];
    const double dist = std::sqrt(block.distance2[c]);
    const double ri = block.radius_i[c], rj = block.radius_j[c];
    ContactGeometry g;
    g.normal = Vec3{block.dx[c], block.dy[c], block.dz[c]} * (1.0 / dist);
    g.overlap = ri + rj - dist;
    PairForce f;
    if constexpr (Central) {  // the law reads the normal, overlap, radii and time step alone
      g.dt = dt;
      g.radius_i = ri;
      g.radius_j = rj;
      f = Law::evaluate_central(g, pair_params);
    } else {
      g.branch_i = ri - 0.5 * g.overlap;
      g.branch_j = rj - 0.5 * g.overlap;
      const Vec3 wi{block.wix[c], block.wiy[c], block.wiz[c]}, wj{block.wjx[c], block.wjy[c], block.wjz[c]};
      g.relative_velocity = Vec3{block.vjx[c], block.vjy[c], block.vjz[c]} -
                            Vec3{block.vix[c], block.viy[c], block.viz[c]} -
                            cross(g.branch_j * wj + g.branch_i * wi, g.normal);
      g.mean_spin = 0.5 * (wi + wj);
      g.dt = dt;
      g.radius_i = ri;
      g.radius_j = rj;
      // Two fixed particles: 0, not infinity, so no NaN reaches them.
      const double inverse_sum = block.inverse_mass_i[c] + block.inverse_mass_j[c];
      g.effective_mass = 1.0 / std::max(inverse_sum, std::numeric_limits<double>::min()) * (inverse_sum > 0.0);
      g.spin_i = wi;
      g.spin_j = wj;
      typename Law::History h = block.history[c];
      f = Law::evaluate(g, pair_params, h);
      updated[c] = h;
      block.torque_i_x[c] = f.torque_i.x;
      block.torque_i_y[c] = f.torque_i.y;
      block.torque_i_z[c] = f.torque_i.z;
      block.torque_j_x[c] = f.torque_j.x;
      block.torque_j_y[c] = f.torque_j.y;
      block.torque_j_z[c] = f.torque_j.z;
    }
    block.force_x[c] = f.force_on_j.x;
    block.force_y[c] = f.force_on_j.y;
    block.force_z[c] = f.force_on_j.z;
    block.stiffness[c] = f.stiffness;
    block.stiffness_over_mass[c] = f.stiffness * std::max(block.inverse_mass_i[c], block.inverse_mass_j[c]);
    if constexpr (Measure) {
      block.energy[c] = f.energy;
      block.force_norm[c] = norm(f.force_on_j);
      block.overlap[c] = g.overlap;
    }
  }
  if constexpr (!Central)
    for (int c = 0; c < count; ++c)
      if (!block.evaluated_before[c]) history[block.pair[c]] = updated[c];
}

template <class BondLaw, bool Measure>
void Engine::bond_contribution(BondModel<BondLaw>& model, std::size_t b, Contribution& out, ThreadWork& work,
                               bool crossing) {
  out = Contribution{};
  const int i = bonds_.i[b], j = bonds_.j[b];
  // Oriented from the bond's owner (the smaller index) to the other particle.
  const bool owner_is_i = i <= j;
  out.particle_j = owner_is_i ? j : i;
  if (bonds_.state[b] != 0) return;
  const auto& P = particles_;
  const Vec3 d = bond_vector(b);
  const double dist = norm(d);
  if (!(dist > 0.0)) return;  // coincident centres: no direction to act along
  ContactGeometry g = pair_geometry(static_cast<std::size_t>(i), static_cast<std::size_t>(j), d, dist);
  g.rest_length = bonds_.rest_length[b];
  const auto& params = model.params(bonds_.material[b]);
  const BondForce f = BondLaw::evaluate(g, params, model.history[b]);
  if (f.failed) {
    ++work.totals.bond_breaks;
    work.failed_bonds.push_back(static_cast<int>(b));
    // The bond's midpoint now, before any particle moves (wrapped into the box after the region).
    try {
      work.failed_positions.push_back(P.position[static_cast<std::size_t>(i)] + 0.5 * d);
    } catch (...) {
      work.failed_positions_full = true;  // nothing may leave the parallel region
    }
  }
  if (f.broken) {
    bonds_.state[b] = 1;
    ++work.totals.bonds_removed;  // its pair may act from the next step: the near list is stale
    // The pair interacts through the contact law from the next step on. The pair belongs to
    // the bond's owner, so only this thread writes its flag; a crossing pair may be evaluated
    // by another thread before the barrier, so its flag waits until after it.
    if (crossing) {
      work.broken_crossing_bonds.push_back(static_cast<int>(b));
      return;
    }
    if (const int p = listed_pair_of(b); p >= 0) pair_bonded_[static_cast<std::size_t>(p)] = 0;
    return;
  }
  const double k = BondLaw::stiffness(params, P.radius[i], P.radius[j], bonds_.rest_length[b]);
  work.totals.max_stiffness_over_mass =
      std::max(work.totals.max_stiffness_over_mass, k * std::max(P.inverse_mass[i], P.inverse_mass[j]));
  out.force_on_j = owner_is_i ? f.force_on_j : -f.force_on_j;
  out.torque_i = owner_is_i ? f.torque_i : f.torque_j;
  out.torque_j = owner_is_i ? f.torque_j : f.torque_i;
  out.stiffness = k;
  if constexpr (Measure) {
    ++work.totals.contacts;
    out.energy = f.energy;
    out.force_norm = norm(f.force_on_j);
  }
}

template <class Law, bool Measure, bool SumRule, bool Integrate>
void Engine::pair_forces(ContactModel<Law>& model, Totals& totals) {
  static_assert(!(Integrate && Measure), "measured steps integrate after the force region");
  const bool step_from_forces = this->step_from_forces();
  const int n = static_cast<int>(particles_.size());
  const int T = threads_;
  const bool any_bonds = !bonds_.i.empty();
  const bool one_type = model.type_count == 1;
  const int* __restrict first = neighbors_.first_pairs().data();
  Vec3* __restrict force = particles_.force.data();
  Vec3* __restrict torque = particles_.torque.data();
  if constexpr (SumRule) stiffness_sum_.resize(static_cast<std::size_t>(n));
  double* __restrict stiffness = SumRule ? stiffness_sum_.data() : nullptr;
  if constexpr (Measure) {
    measure_energy_.assign(static_cast<std::size_t>(n), 0.0);
    measure_force_.assign(static_cast<std::size_t>(n), 0.0);
  }
  double* __restrict measure_energy = Measure ? measure_energy_.data() : nullptr;
  double* __restrict measure_force = Measure ? measure_force_.data() : nullptr;
  constexpr int capacity = PairBlock<Law>::capacity;
  // No torque can act (spin_free_) and the law has a central form: evaluate only that. The
  // engine decided this once (engine.cpp): it is exactly where it keeps no pair histories.
  constexpr bool has_central = has_central_form<Law>;
  const bool central = has_central && !pair_histories_;
  if (!walls_.empty()) wall_chunk_force_.resize(static_cast<std::size_t>(chunk_count(n)) * walls_.size());

  // What a pair or bond gives its owner and its other particle.
  auto add_to_owner = [&](int i, const Contribution& c) {
    force[i] -= c.force_on_j;
    torque[i] += c.torque_i;
    if constexpr (SumRule) stiffness[i] += c.stiffness;
    if constexpr (Measure) {
      measure_energy[i] += c.energy;
      measure_force[i] += c.force_norm;
    }
  };
  auto add_to_other = [&](const Contribution& c) {
    force[c.particle_j] += c.force_on_j;
    torque[c.particle_j] += c.torque_j;
    if constexpr (SumRule) stiffness[c.particle_j] += c.stiffness;
  };
  // Measured steps: contact counts and the largest overlap ratio of a block's acting pairs.
  auto measure_block = [&](const PairBlock<Law>& block, Totals& local) {
    if constexpr (Measure)
      for (int c = 0; c < block.count; ++c) {
        if (block.evaluated_before[c]) continue;
        local.contacts += block.overlap[c] > 0.0;
        local.max_overlap_ratio =
            std::max(local.max_overlap_ratio, block.overlap[c] / (block.radius_i[c] + block.radius_j[c]));
      }
  };

#pragma omp parallel num_threads(T)
  {
    const int t = omp_get_thread_num();
    ThreadWork& work = work_[static_cast<std::size_t>(t)];
    work.totals = Totals{};
    work.failed_bonds.clear();
    work.failed_positions.clear();
    work.failed_positions_full = false;
    work.broken_crossing_bonds.clear();
    Totals& local = work.totals;
    PairBlock<Law> block;
    const std::uint8_t no_crossing = 0;
    const std::uint8_t* crossing_acts = work.crossing_pair_acts.empty() ? &no_crossing : work.crossing_pair_acts.data();
    int crossing_seen = 0;
    // Gathers and evaluates one block of listed pairs.
    auto evaluate_block = [&]<bool Indirect, bool Guarded, bool Central>(const int* list, const int* owners, int start,
                                                                         int count, int skip_from) {
      if (one_type) {
        gather_pairs<Law, true, Indirect, Guarded, Central>(model, list, owners, start, count, skip_from,
                                                            crossing_acts, crossing_seen, block);
        contact_block<Law, true, Measure, Central>(model, block);
      } else {
        gather_pairs<Law, false, Indirect, Guarded, Central>(model, list, owners, start, count, skip_from,
                                                             crossing_acts, crossing_seen, block);
        contact_block<Law, false, Measure, Central>(model, block);
      }
    };
    auto run_block = [&]<bool Indirect, bool Guarded>(const int* list, const int* owners, int start, int count,
                                                      int skip_from) {
      if constexpr (has_central) {
        if (central)
          evaluate_block.template operator()<Indirect, Guarded, true>(list, owners, start, count, skip_from);
        else
          evaluate_block.template operator()<Indirect, Guarded, false>(list, owners, start, count, skip_from);
      } else {
        evaluate_block.template operator()<Indirect, Guarded, false>(list, owners, start, count, skip_from);
      }
      for (int c = 0; c < block.count; ++c)
        if (!block.evaluated_before[c])
          local.max_stiffness_over_mass = std::max(local.max_stiffness_over_mass, block.stiffness_over_mass[c]);
      measure_block(block, local);
    };
    auto block_result = [&](int c) {
      Contribution r;
      r.particle_j = block.other[c];
      r.force_on_j = {block.force_x[c], block.force_y[c], block.force_z[c]};
      if (!central) {  // else zero, as the law would give
        r.torque_i = {block.torque_i_x[c], block.torque_i_y[c], block.torque_i_z[c]};
        r.torque_j = {block.torque_j_x[c], block.torque_j_y[c], block.torque_j_z[c]};
      }
      r.stiffness = block.stiffness[c];
      if constexpr (Measure) {
        r.energy = block.energy[c];
        r.force_norm = block.force_norm[c];
      }
      return r;
    };
    const int begin = work.particle_begin, end = work.particle_end;

    // 1. The pairs and bonds that reach a later thread's particles, kept for both sides. The
    // crossing pairs of all threads, in thread order, are shared out so that every thread has
    // about the same work before the barrier (its own crossing bonds counted); a pair's result
    // does not depend on which thread evaluates it. Evaluated by their owners
    // alone, they kept the later threads waiting at the barrier.
    if (T > 1) {
      // This thread's slice [lo, hi) of the concatenated crossing pairs (partition_work).
      const long lo = work.crossing_slice_begin, hi = work.crossing_slice_end;
      long offset = 0;
      for (int s = 0; s < T && offset < hi; ++s) {
        ThreadWork& owner_work = work_[static_cast<std::size_t>(s)];
        const long size = static_cast<long>(owner_work.crossing_pairs.size());
        const int from = static_cast<int>(std::max(lo, offset) - offset);
        const int to = static_cast<int>(std::min(hi, offset + size) - offset);
        offset += size;
        if (from >= to) continue;
        std::fill(owner_work.crossing_pair_acts.begin() + from, owner_work.crossing_pair_acts.begin() + to, 0);
        for (int s0 = from; s0 < to; s0 += capacity) {
          const int count = std::min(capacity, to - s0);
          run_block.template operator()<true, false>(owner_work.crossing_pairs.data(),
                                                     owner_work.crossing_pair_owners.data(), s0, count, INT_MAX);
          // The acting ones, in list order: find each one's place among the crossing pairs.
          int k = s0;
          for (int c = 0; c < block.count; ++c) {
            while (owner_work.crossing_pairs[static_cast<std::size_t>(k)] != block.pair[c]) ++k;
            owner_work.crossing_pair_results[static_cast<std::size_t>(k)] = block_result(c);
            owner_work.crossing_pair_acts[static_cast<std::size_t>(k)] = 1;
          }
        }
      }
      crossing_seen = 0;
      if (any_bonds)
        std::visit(
            [&](auto& bonds) {
              using BondLaw = std::decay_t<decltype(bonds.law)>;
              for (std::size_t c = 0; c < work.crossing_bonds.size(); ++c)
                bond_contribution<BondLaw, Measure>(bonds, static_cast<std::size_t>(work.crossing_bonds[c]),
                                                    work.crossing_bond_results[c], work, true);
            },
            bond_model_);
#pragma omp barrier
      for (const int b : work.broken_crossing_bonds)
        if (const int p = listed_pair_of(static_cast<std::size_t>(b)); p >= 0)
          pair_bonded_[static_cast<std::size_t>(p)] = 0;
    }

    // 2. This thread's particles: what earlier threads' acting crossing pairs give them, then
    // the own pairs in list order (a crossing pair's own side from step 1).
    std::fill(force + begin, force + end, Vec3{});
    std::fill(torque + begin, torque + end, Vec3{});
    if constexpr (SumRule) std::fill(stiffness + begin, stiffness + end, 0.0);
    for (int s = 0; s < t; ++s) {
      const ThreadWork& earlier = work_[static_cast<std::size_t>(s)];
      for (std::size_t c = 0; c < earlier.crossing_pair_results.size(); ++c) {
        const Contribution& r = earlier.crossing_pair_results[c];
        if (earlier.crossing_pair_acts[c] && r.particle_j >= begin && r.particle_j < end) add_to_other(r);
      }
    }
    std::size_t crossing_index = 0;
    // The pairs come owner by owner, and a pair (i, j) has j > i (or j == i, a self image), so
    // from the owner's first pair on nothing else adds to its force until its last: its sums
    // stay in registers (loaded at its first pair, stored after its last), the same additions
    // in the same order as adding to memory pair by pair, without two loads and stores per pair.
    struct OwnerSums {
      Vec3* __restrict force_out;
      Vec3* __restrict torque_out;
      double* __restrict stiffness_out;  // SumRule only
      int index = -1;
      Vec3 force{}, torque{};
      double stiffness = 0.0;
      // Stores the sums of the current owner (if any) and loads those of owner k (-1: none).
      void take(int k) {
        if (index >= 0) {
          force_out[index] = force;
          torque_out[index] = torque;
          if constexpr (SumRule) stiffness_out[index] = stiffness;
        }
        index = k;
        if (k < 0) return;
        force = force_out[k];
        torque = torque_out[k];
        if constexpr (SumRule) stiffness = stiffness_out[k];
      }
    } owner{force, torque, stiffness};
    // Each listed pair's particle i, walked along with the blocks (not stored per pair: issue
    // #14, bytes per particle).
    int block_owner[capacity];
    int owner_now = begin;
    // The near list's pairs (a subsequence of the listed ones: the same acting pairs in the
    // same order), or every listed pair of the range.
    const int near_count = near_active_ ? static_cast<int>(work.near_pairs.size()) : 0;
    const int walk_begin = near_active_ ? 0 : first[begin];
    const int walk_end = near_active_ ? near_count : first[end];
    for (int p0 = walk_begin; p0 < walk_end; p0 += capacity) {
      const int count = std::min(capacity, walk_end - p0);
      // Guarded only where another thread may be moving this range's crossing partners.
      if (near_active_) {
        if (Integrate && end < n)
          run_block.template operator()<true, Integrate>(work.near_pairs.data(), work.near_owners.data(), p0, count,
                                                         end);
        else
          run_block.template operator()<true, false>(work.near_pairs.data(), work.near_owners.data(), p0, count, end);
      } else {
        for (int k = 0; k < count; ++k) {
          while (first[owner_now + 1] <= p0 + k) ++owner_now;
          block_owner[k] = owner_now;
        }
        if (Integrate && end < n)
          run_block.template operator()<false, Integrate>(nullptr, block_owner, p0, count, end);
        else
          run_block.template operator()<false, false>(nullptr, block_owner, p0, count, end);
      }
      for (int c = 0; c < block.count; ++c) {
        const int i = block.owner[c], j = block.other[c];
        if (i != owner.index) owner.take(i);
        if (block.evaluated_before[c]) {
          while (work.crossing_pairs[crossing_index] != block.pair[c]) ++crossing_index;
          const Contribution& r = work.crossing_pair_results[crossing_index];
          owner.force -= r.force_on_j;
          owner.torque += r.torque_i;
          if constexpr (SumRule) owner.stiffness += r.stiffness;
          if constexpr (Measure) {
            measure_energy[i] += r.energy;
            measure_force[i] += r.force_norm;
          }
          continue;
        }
        const Vec3 f{block.force_x[c], block.force_y[c], block.force_z[c]};
        owner.force -= f;
        if (!central) owner.torque += Vec3{block.torque_i_x[c], block.torque_i_y[c], block.torque_i_z[c]};
        if constexpr (SumRule) owner.stiffness += block.stiffness[c];
        if (j == i) {  // a self image: both sides are the owner, in the same order
          owner.force += f;
          if (!central) owner.torque += Vec3{block.torque_j_x[c], block.torque_j_y[c], block.torque_j_z[c]};
          if constexpr (SumRule) owner.stiffness += block.stiffness[c];
        } else {
          force[j] += f;
          if (!central) torque[j] += Vec3{block.torque_j_x[c], block.torque_j_y[c], block.torque_j_z[c]};
          if constexpr (SumRule) stiffness[j] += block.stiffness[c];
        }
        if constexpr (Measure) {
          measure_energy[i] += block.energy[c];
          measure_force[i] += block.force_norm[c];
        }
      }
    }
    owner.take(-1);

    // 3. Bonds the same way: earlier threads' crossing bonds, then the own ones in order.
    if (any_bonds) {
      for (int s = 0; s < t; ++s)
        for (const Contribution& c : work_[static_cast<std::size_t>(s)].crossing_bond_results)
          if (c.particle_j >= begin && c.particle_j < end) add_to_other(c);
      std::visit(
          [&](auto& bonds) {
            using BondLaw = std::decay_t<decltype(bonds.law)>;
            std::size_t crossing_bonds_seen = 0;
            Contribution c;
            for (int bond = bond_first_[begin]; bond < bond_first_[end]; ++bond) {
              const auto b = static_cast<std::size_t>(bond);
              const int bond_owner = std::min(bonds_.i[b], bonds_.j[b]);
              if (std::max(bonds_.i[b], bonds_.j[b]) >= end) {
                add_to_owner(bond_owner, work.crossing_bond_results[crossing_bonds_seen++]);
                continue;
              }
              bond_contribution<BondLaw, Measure>(bonds, b, c, work);
              add_to_owner(bond_owner, c);
              add_to_other(c);
            }
          },
          bond_model_);
    }

    // 4. Walls: per particle, over fixed chunks (the wall forces are sums over particles).
    if (!walls_.empty()) {
#pragma omp barrier
      local.max_stiffness_over_mass =
          std::max(local.max_stiffness_over_mass,
                   wall_forces<Law, Measure>(model, stiffness, measure_energy, measure_force, &local.contacts));
    }

    if constexpr (SumRule) {
      // The stiffest particle: sum of its contact stiffnesses over its mass (fixed particles
      // have zero inverse mass and drop out).
      const double* __restrict inverse_mass = particles_.inverse_mass.data();
      double largest = 0.0;
      for (int k = begin; k < end; ++k) largest = std::max(largest, stiffness[k] * inverse_mass[k]);
      local.max_stiffness_over_mass = largest;
    }

    // 5. This thread's particles move, while their forces are in its cache (fixed chunks made
    // two threads' integration cost 5x one thread's CPU time in the shear benchmark, its 3
    // chunks split 2 : 1; a second region cost a fork). No other thread reads them any more in
    // this step: after the barrier each thread reads only its own particles, the kept results
    // of the crossing pairs and bonds, and (walls) what the wall loop's closing barrier has
    // finished. A time step taken from this step's forces needs every thread's largest
    // stiffness over mass first: one barrier, then each thread finds the same step (a max does
    // not depend on the order) that step_impl stores after the region.
    if constexpr (Integrate) {
      double dt = dt_;
      if (step_from_forces) {
#pragma omp barrier
        double largest = 0.0;
        for (int s = 0; s < T; ++s)
          largest = std::max(largest, work_[static_cast<std::size_t>(s)].totals.max_stiffness_over_mass);
        dt = time_step_from_stiffness(largest);
      }
      local.max_speed2 = advance_particles(begin, end, dt);
    }
  }

  // Order-independent reductions (max, counts) over threads; sums in particle order.
  std::size_t first_break = breaks_.size();
  for (int t = 0; t < T; ++t) {
    const ThreadWork& work = work_[static_cast<std::size_t>(t)];
    totals.max_stiffness_over_mass = std::max(totals.max_stiffness_over_mass, work.totals.max_stiffness_over_mass);
    totals.bond_breaks += work.totals.bond_breaks;
    totals.max_speed2 = std::max(totals.max_speed2, work.totals.max_speed2);
    if (work.totals.bonds_removed > 0) near_stale_ = true;
    // Where each failed: the middle of the bond at this step's force evaluation.
    if (work.failed_positions_full) throw std::bad_alloc();
    for (std::size_t k = 0; k < work.failed_bonds.size(); ++k)
      breaks_.push_back(
          BondBreak{static_cast<std::size_t>(bond_input_index_[static_cast<std::size_t>(work.failed_bonds[k])]), time_,
                    packing_.box.wrap(work.failed_positions[k])});
    if constexpr (Measure) {
      totals.contacts += work.totals.contacts;
      totals.max_overlap_ratio = std::max(totals.max_overlap_ratio, work.totals.max_overlap_ratio);
    }
  }
  std::stable_sort(breaks_.begin() + static_cast<std::ptrdiff_t>(first_break), breaks_.end(),
                   [](const BondBreak& a, const BondBreak& b) { return a.bond < b.bond; });
  broken_bonds_ += totals.bond_breaks;
  for (std::size_t m = 0; m < walls_.size(); ++m) {
    Vec3 sum{};
    for (int c = 0; c < chunk_count(n); ++c) sum += wall_chunk_force_[static_cast<std::size_t>(c) * walls_.size() + m];
    wall_force_[m] = sum;
  }
  if constexpr (Measure) {
    for (int k = 0; k < n; ++k) {
      totals.strain_energy += measure_energy[k];
      totals.contact_force_sum += measure_force[k];
    }
  }
}

template <class Law, bool Measure>
double Engine::wall_forces(ContactModel<Law>& model, double* stiffness, double* measure_energy, double* measure_force,
                           std::size_t* wall_contacts) {
  const int n = static_cast<int>(particles_.size());
  const std::size_t walls = walls_.size();
  const int chunks = chunk_count(n);
  const auto& P = particles_;
  Vec3* force = particles_.force.data();
  Vec3* torque = particles_.torque.data();
  std::size_t contacts = 0;
  double max_stiffness_over_mass = 0.0;
#pragma omp for schedule(static)
  for (int c = 0; c < chunks; ++c) {
    Vec3* chunk_force = &wall_chunk_force_[static_cast<std::size_t>(c) * walls];
    std::fill(chunk_force, chunk_force + walls, Vec3{});
    for (int k = c * chunk_size; k < std::min(n, (c + 1) * chunk_size); ++k) {
      for (std::size_t m = 0; m < walls; ++m) {
        const Wall& wall = walls_[m];
        const double distance = dot(P.position[k] - wall.point, wall.normal);
        auto& history = model.wall_history[static_cast<std::size_t>(k) * walls + m];
        const int t = P.type[k];
        const auto& params = model.params(t, t);
        if (distance >= P.radius[k] + Law::reach(params)) {
          history = typename Law::History{};
          continue;
        }
        const ContactGeometry g = wall_geometry(static_cast<std::size_t>(k), wall, distance);
        const PairForce f = Law::evaluate(g, params, history);
        force[k] -= f.force_on_j;
        torque[k] += f.torque_i;
        chunk_force[m] += f.force_on_j;
        max_stiffness_over_mass = std::max(max_stiffness_over_mass, f.stiffness * P.inverse_mass[k]);
        if (stiffness) stiffness[k] += f.stiffness;
        if constexpr (Measure) {
          contacts += g.overlap > 0.0;
          measure_energy[k] += f.energy;
          measure_force[k] += norm(f.force_on_j);
        }
      }
    }
  }
  *wall_contacts += contacts;
  return max_stiffness_over_mass;
}

double Engine::advance_particles(int begin, int end, double dt) {
  auto& P = particles_;
  const double* __restrict damping = type_damping_.data();
  const int* __restrict type = P.type.data();
  double max_speed2 = 0.0;
  // Without torques (spin_free_) the spins cannot change: the rotation's update is skipped,
  // which changes no bit (the torque is zero, so its damped value and the spin increment are).
  const auto advance = [&]<bool Rotate>() {
    for (int i = begin; i < end; ++i) {
      // Fixed particles have zero inverse mass and inertia: they keep zero velocity without a
      // branch, so the loop vectorizes.
      const double alpha = damping[type[i]];
      const Vec3 f = apply_local_damping(P.force[i], P.velocity[i], alpha);
      P.velocity[i] += (P.inverse_mass[i] * dt) * f;
      if constexpr (Rotate) {
        const Vec3 m = apply_local_damping(P.torque[i], P.angular_velocity[i], alpha);
        P.angular_velocity[i] += (P.inverse_inertia[i] * dt) * m;
      }
      P.position[i] += dt * P.velocity[i];
      // Each particle moved dt |v| (the near list's drift, dem/near_pairs.cpp).
      const double speed2 = norm2(P.velocity[i]);
      max_speed2 = speed2 > max_speed2 ? speed2 : max_speed2;
    }
  };
  if (spin_free_)
    advance.template operator()<false>();
  else
    advance.template operator()<true>();
  return max_speed2;
}

void Engine::integrate_measured(Totals& totals) {
  const int n = static_cast<int>(particles_.size());
  const double dt = dt_;
  auto& P = particles_;
  const int chunks = chunk_count(n);
  chunk_sums_.assign(3 * static_cast<std::size_t>(chunks), 0.0);
  chunk_max_speed2_.assign(static_cast<std::size_t>(chunks), 0.0);
  const double* __restrict damping = type_damping_.data();
  const int* __restrict type = P.type.data();
  // Fixed chunks, whose sums are the same at any thread count.
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (int c = 0; c < chunks; ++c) {
    double kinetic = 0.0, unbalanced = 0.0, free_count = 0.0;
    const int chunk_begin = c * chunk_size, chunk_end = std::min(n, (c + 1) * chunk_size);
    // The sums from the state before the update (the synchronous velocity of the kinetic
    // energy is half a step on), then the same update as an unmeasured step.
    for (int i = chunk_begin; i < chunk_end; ++i) {
      if (P.fixed[i]) continue;
      const double alpha = damping[type[i]];
      const Vec3 f = apply_local_damping(P.force[i], P.velocity[i], alpha);
      const Vec3 m = apply_local_damping(P.torque[i], P.angular_velocity[i], alpha);
      const Vec3 v_sync = P.velocity[i] + 0.5 * ((P.inverse_mass[i] * dt) * f);
      const Vec3 w_sync = P.angular_velocity[i] + 0.5 * ((P.inverse_inertia[i] * dt) * m);
      kinetic += 0.5 * (P.mass[i] * norm2(v_sync) + sphere_inertia(P.mass[i], P.radius[i]) * norm2(w_sync));
      unbalanced += norm(P.force[i]);
      free_count += 1.0;
    }
    chunk_max_speed2_[static_cast<std::size_t>(c)] = advance_particles(chunk_begin, chunk_end, dt);
    chunk_sums_[3 * static_cast<std::size_t>(c)] = kinetic;
    chunk_sums_[3 * static_cast<std::size_t>(c) + 1] = unbalanced;
    chunk_sums_[3 * static_cast<std::size_t>(c) + 2] = free_count;
  }
  // Chunk sums in chunk order: the same at any thread count.
  double free_count = 0.0;
  for (int c = 0; c < chunks; ++c) {
    totals.kinetic_energy += chunk_sums_[3 * static_cast<std::size_t>(c)];
    totals.unbalanced_force_sum += chunk_sums_[3 * static_cast<std::size_t>(c) + 1];
    free_count += chunk_sums_[3 * static_cast<std::size_t>(c) + 2];
    totals.max_speed2 = std::max(totals.max_speed2, chunk_max_speed2_[static_cast<std::size_t>(c)]);
  }
  totals.free_particles = static_cast<std::size_t>(free_count);
}

bool Engine::step_from_forces() const {
  return config_.time_step <= 0.0 && config_.time_step_rule != TimeStepRule::global;
}

double Engine::time_step_from_stiffness(double max_stiffness_over_mass) const {
  return max_stiffness_over_mass > 0.0
             ? std::min(time_step_cap_, config_.time_step_safety / std::sqrt(max_stiffness_over_mass))
             : time_step_cap_;
}

void Engine::set_active_threads(int threads) {
  if (threads == threads_) return;
  threads_ = threads;
  ++tuning_.switches;
  partition_work();
}

// adapt_threads: runs at the faster of one thread and the configured count. A probe times four
// stretches, alternating the other count and the current best (other, best, other, best), so
// that a load that changes during the probe weighs on both alike; each stretch lasts at least
// 10 timed steps and thread_probe_seconds (0.1 s: many scheduler time slices, so that a busy
// machine's noise, timer resolution and a single neighbour rebuild do not decide). The first
// steps after a switch are not timed (threads woken from sleep, caches of the other layout).
// A probe that favours more threads is repeated at once, and the count goes up only if the
// second agrees: on a loaded machine a single probe sometimes picked the slower count, and
// too many threads there cost more than one thread costs on an idle machine (docs/engine.md,
// "Parallelism"). Going down to one thread takes one probe.
void Engine::tune_threads() {
  ThreadTuning& t = tuning_;
  if (t.configured == 1 || !config_.adapt_threads) return;
  using Clock = std::chrono::steady_clock;
  const auto now = Clock::now();
  const int other = t.best == 1 ? t.configured : 1;
  if (t.phase == 0) {
    if (t.steps_to_probe > 0 ? --t.steps_to_probe > 0 : now < t.next_probe) return;
    t.steps_to_probe = 0;
    t.other_seconds = t.best_seconds = 0.0;
    t.other_steps = t.best_steps = 0;
    t.phase = 1;
    t.phase_steps = 0;
    set_active_threads(other);
  } else {
    if (t.phase_steps == ThreadTuning::untimed_steps) t.phase_start = now;
    const double elapsed =
        t.phase_steps >= ThreadTuning::untimed_steps ? std::chrono::duration<double>(now - t.phase_start).count() : 0.0;
    const long timed_steps = t.phase_steps - ThreadTuning::untimed_steps;
    if (timed_steps >= 10 && elapsed >= config_.thread_probe_seconds) {
      const bool timing_other = t.phase % 2 == 1;
      (timing_other ? t.other_seconds : t.best_seconds) += elapsed;
      (timing_other ? t.other_steps : t.best_steps) += timed_steps;
      if (t.phase == 4) {
        // A 3 % margin: a count that is about as fast does not take over on noise.
        const double other_per_step = t.other_seconds / static_cast<double>(t.other_steps);
        const double best_per_step = t.best_seconds / static_cast<double>(t.best_steps);
        const bool other_faster = other_per_step < 0.97 * best_per_step;
        if (other_faster && other > t.best && !t.confirming) {
          // Probe again at once; go up only if that one agrees.
          t.confirming = true;
          t.other_seconds = t.best_seconds = 0.0;
          t.other_steps = t.best_steps = 0;
          t.phase = 1;
          t.phase_steps = 1;  // this step is the stretch's first, as after every other switch
          set_active_threads(other);
          return;
        }
        if (other_faster) t.best = other;
        t.confirming = false;
        set_active_threads(t.best);
        t.phase = 0;
        t.next_probe = now + std::chrono::duration_cast<Clock::duration>(
                                 std::chrono::duration<double>(config_.thread_probe_every));
        return;
      }
      ++t.phase;
      t.phase_steps = 0;
      set_active_threads(t.phase % 2 == 1 ? other : t.best);
    }
  }
  ++t.phase_steps;
}

template <bool Measure>
Engine::Totals Engine::step_impl() {
  tune_threads();
  if (neighbors_.needs_rebuild(particles_.position, particles_.radius)) refresh_neighbors();
  if (near_list_due()) refresh_near_pairs();
  Totals totals;
  // An unmeasured step integrates inside the force region (one fork and join of the threads
  // per step); a measured one after it, over the fixed chunks of its sums.
  std::visit(
      [&](auto& model) {
        using Law = std::decay_t<decltype(model.law)>;
        constexpr bool integrate_in_region = !Measure;
        if (config_.time_step <= 0.0 && config_.time_step_rule == TimeStepRule::stiffness_sum)
          pair_forces<Law, Measure, true, integrate_in_region>(model, totals);
        else
          pair_forces<Law, Measure, false, integrate_in_region>(model, totals);
      },
      model_);
  if (step_from_forces()) dt_ = time_step_from_stiffness(totals.max_stiffness_over_mass);
  if constexpr (Measure) integrate_measured(totals);
  last_max_speed_ = std::sqrt(totals.max_speed2);
  near_drift_ += dt_ * last_max_speed_;
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
  // A run that turned non-finite stops at the first measured step after it, naming a particle,
  // rather than writing NaN curves and failing later at an output (or not at all).
  if (!std::isfinite(d.kinetic_energy) || !std::isfinite(d.strain_energy)) {
    const auto& P = particles_;
    std::size_t k = 0;
    while (k < n && std::isfinite(norm2(P.position[k])) && std::isfinite(norm2(P.velocity[k])) &&
           std::isfinite(norm2(P.force[k])))
      ++k;
    const std::string which =
        k < n ? fmt::format("particle {} (position ({:g}, {:g}, {:g}), velocity ({:g}, {:g}, {:g}))",
                            original_index_[k], P.position[k].x, P.position[k].y, P.position[k].z, P.velocity[k].x,
                            P.velocity[k].y, P.velocity[k].z)
              : std::string("the strain energy");
    fail_input(fmt::format(
        "step {}: the run became non-finite at {}: unstable; likely a time step too large for the stiffest "
        "contact or bond (lower time_step_safety or time_step) or particles overlapping far beyond the contact law",
        d.step, which));
  }
  return d;
}

}  // namespace packlab::dem
