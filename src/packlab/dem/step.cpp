// One time step: the threaded loop over the listed pairs (the contact law), the bonds (the
// bond law) and the walls, then the leap-frog integration with local damping and the
// refreshed time step. Everything in the loop is templated on the laws (dem/contact/,
// dem/bond/), so each law gets its own inlined loop and adding one touches nothing here.
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "packlab/dem/engine.hpp"
#include "packlab/dem/local_damping.hpp"

namespace packlab::dem {

template <class Law, bool Measure>
void Engine::wall_forces(ContactModel<Law>& model, int thread, Vec3* force, Vec3* torque, double* stiffness,
                         Totals& local) {
  const std::size_t n = particles_.size(), walls = walls_.size();
  const std::size_t begin = n * thread / threads_, end = n * (thread + 1) / threads_;
  auto& wall_force = thread_wall_force_[thread];
  wall_force.assign(walls, Vec3{});
  const auto& P = particles_;
  for (std::size_t k = begin; k < end; ++k) {
    for (std::size_t m = 0; m < walls; ++m) {
      const Wall& wall = walls_[m];
      const double distance = dot(P.position[k] - wall.point, wall.normal);
      auto& history = model.wall_history[k * walls + m];
      const int t = P.type[k];
      const auto& params = model.params(t, t);
      if (distance >= P.radius[k] + Law::reach(params)) {
        history = typename Law::History{};
        continue;
      }
      const ContactGeometry g = wall_geometry(k, wall, distance);
      const PairForce f = Law::evaluate(g, params, history);
      force[k] -= f.force_on_j;
      torque[k] += f.torque_i;
      wall_force[m] += f.force_on_j;
      local.max_stiffness_over_mass = std::max(local.max_stiffness_over_mass, f.stiffness * P.inverse_mass[k]);
      if (stiffness) stiffness[k] += f.stiffness;
      if constexpr (Measure) {
        local.contacts += g.overlap > 0.0;
        local.contact_force_sum += norm(f.force_on_j);
        local.strain_energy += f.energy;
      }
    }
  }
}

template <class BondLaw, bool Measure>
void Engine::bond_forces(BondModel<BondLaw>& model, int thread, Vec3* force, Vec3* torque, double* stiffness,
                         Totals& local) {
  auto& histories = model.history;
  const std::size_t nb = bonds_.i.size();
  const std::size_t begin = nb * thread / threads_, end = nb * (thread + 1) / threads_;
  const auto& P = particles_;
  const Box& box = packing_.box;
  for (std::size_t b = begin; b < end; ++b) {
    if (bonds_.state[b] != 0) continue;
    const int i = bonds_.i[b], j = bonds_.j[b];
    const Vec3 d = P.position[j] + box.shift_vector(bond_image_now(b)) - P.position[i];
    const double dist = norm(d);
    if (!(dist > 0.0)) continue;  // coincident centres: no direction to act along
    ContactGeometry g = pair_geometry(static_cast<std::size_t>(i), static_cast<std::size_t>(j), d, dist);
    g.rest_length = bonds_.rest_length[b];
    const auto& params = model.params(bonds_.material[b]);
    const BondForce f = BondLaw::evaluate(g, params, histories[b]);
    if (f.failed) {
      ++local.bond_breaks;
      thread_breaks_[thread].push_back(BondBreak{b, time_, box.wrap(P.position[i] + 0.5 * d)});
    }
    if (f.broken) {
      bonds_.state[b] = 1;
      // The pair interacts through the contact law from the next step on. Only this thread
      // touches bond b and its pair.
      if (bonds_.pair[b] >= 0) pair_bonded_[static_cast<std::size_t>(bonds_.pair[b])] = 0;
      continue;
    }
    force[i] -= f.force_on_j;
    force[j] += f.force_on_j;
    torque[i] += f.torque_i;
    torque[j] += f.torque_j;
    const double k = BondLaw::stiffness(params, P.radius[i], P.radius[j], bonds_.rest_length[b]);
    local.max_stiffness_over_mass = std::max(local.max_stiffness_over_mass, k * std::max(P.inverse_mass[i], P.inverse_mass[j]));
    if (stiffness) {
      stiffness[i] += k;
      stiffness[j] += k;
    }
    if constexpr (Measure) {
      local.contact_force_sum += norm(f.force_on_j);
      ++local.contacts;
      local.strain_energy += f.energy;
    }
  }
}

template <class Law, bool Measure, bool SumRule>
void Engine::pair_forces(ContactModel<Law>& model, Totals& totals) {
  const int n = static_cast<int>(particles_.size());
  const int T = threads_;
  const Vec3* __restrict x = particles_.position.data();
  const Vec3* __restrict v = particles_.velocity.data();
  const Vec3* __restrict w = particles_.angular_velocity.data();
  const double* __restrict rad = particles_.radius.data();
  const int* __restrict type = particles_.type.data();
  const int* __restrict first = neighbors_.first_pairs().data();
  const int* __restrict partner = neighbors_.partner().data();
  const std::uint8_t* __restrict image = neighbors_.image().data();
  const int pair_total = first[n];
  const double dt = dt_;
  const int type_count = model.type_count;
  const auto* __restrict params = model.pair_params.data();
  const double* __restrict inverse_mass = particles_.inverse_mass.data();
  auto* __restrict history = model.history.data();
  const std::uint8_t* __restrict bonded = pair_bonded_.data();
  const bool any_bonded = !bonds_.i.empty();
  constexpr bool sum_rule = SumRule;
  if constexpr (sum_rule) thread_stiffness_.resize(static_cast<std::size_t>(T));
  // Several threads and only pair contacts: each thread owns its range of particles and writes
  // their forces directly; a contribution to a particle of a later thread's range goes to a
  // short "ghost" list, added by its owner after the barrier. (With bonds or walls, whose loops
  // are split differently, each thread sums into a whole-size buffer instead; zeroing and
  // summing those buffers costs as much as a sparse packing's contacts.)
  const bool owned = T > 1 && !any_bonded && walls_.empty();
  if (owned) {
    thread_ghosts_.resize(static_cast<std::size_t>(T));
    if constexpr (sum_rule) shared_stiffness_.resize(static_cast<std::size_t>(n));
  }
  std::array<Vec3, 27> offsets;  // local copy: the force stores below cannot alias it
  for (int c = 0; c < 27; ++c) offsets[c] = neighbors_.image_offset(c);

#pragma omp parallel num_threads(T)
  {
    const int t = omp_get_thread_num();
    // Contiguous ranges of particles holding about equal numbers of pairs; each particle's
    // pairs belong to one thread, so its own force is summed in registers.
    auto first_particle = [&](int thread) {
      return static_cast<int>(std::lower_bound(first, first + n, static_cast<int>(static_cast<long>(pair_total) *
                                                                                   thread / T)) -
                              first);
    };
    const int i_begin = first_particle(t);
    const int i_end = t + 1 == T ? n : first_particle(t + 1);
    Vec3* __restrict force;
    Vec3* __restrict torque;
    double* __restrict stiffness = nullptr;
    if (T == 1 || owned) {
      force = particles_.force.data();
      torque = particles_.torque.data();
      // Owned: zero only this thread's range (no other thread writes it before the barrier).
      const int zero_begin = owned ? i_begin : 0, zero_end = owned ? i_end : n;
      std::fill(force + zero_begin, force + zero_end, Vec3{});
      std::fill(torque + zero_begin, torque + zero_end, Vec3{});
      if constexpr (sum_rule) {
        std::vector<double>& buffer = owned ? shared_stiffness_ : thread_stiffness_[t];
        buffer.resize(static_cast<std::size_t>(n));
        stiffness = buffer.data();
        std::fill(stiffness + zero_begin, stiffness + zero_end, 0.0);
      }
      if (owned) thread_ghosts_[t].clear();
    } else {
      thread_force_[t].resize(n);
      thread_torque_[t].resize(n);
      force = thread_force_[t].data();
      torque = thread_torque_[t].data();
      std::fill(force, force + n, Vec3{});
      std::fill(torque, torque + n, Vec3{});
      if constexpr (sum_rule) {
        thread_stiffness_[t].assign(n, 0.0);
        stiffness = thread_stiffness_[t].data();
      }
    }
    std::vector<Ghost>* ghosts = owned ? &thread_ghosts_[t] : nullptr;
    Totals local;
    for (int i = i_begin; i < i_end; ++i) {
      const Vec3 xi = x[i], vi = v[i], wi = w[i];
      const double ri = rad[i];
      const double inverse_mass_i = inverse_mass[i];
      const auto* params_i = params + type[i] * type_count;
      Vec3 force_i{}, torque_i{};
      double stiffness_i = 0.0;
      for (int p = first[i]; p < first[i + 1]; ++p) {
        const int j = partner[p];
        const Vec3 d = x[j] + offsets[image[p]] - xi;
        const double dist2 = norm2(d);
        const double rsum = ri + rad[j];
        const auto& pair_params = params_i[type[j]];
        const double cutoff = rsum + Law::reach(pair_params);  // rsum for laws acting on overlap only
        if (dist2 >= cutoff * cutoff || (any_bonded && bonded[p])) {
          // Out of range (its history ends), or bonded (the bond law acts instead).
          history[p] = typename Law::History{};
          continue;
        }
        const double dist = std::sqrt(dist2);
        // pair_geometry() inlined with particle i's data held in registers (hot loop).
        ContactGeometry g;
        g.normal = d * (1.0 / dist);
        g.overlap = rsum - dist;
        g.branch_i = ri - 0.5 * g.overlap;
        g.branch_j = rad[j] - 0.5 * g.overlap;
        g.relative_velocity = v[j] - vi - cross(g.branch_j * w[j] + g.branch_i * wi, g.normal);
        g.mean_spin = 0.5 * (wi + w[j]);
        g.dt = dt;
        // Unused by laws that do not need them (the compiler drops the loads).
        g.radius_i = ri;
        g.radius_j = rad[j];
        // Two fixed particles: 0, not infinity (a select, no branch), so no NaN reaches them.
        const double inverse_sum = inverse_mass_i + inverse_mass[j];
        g.effective_mass = inverse_sum > 0.0 ? 1.0 / inverse_sum : 0.0;
        g.spin_i = wi;
        g.spin_j = w[j];
        const PairForce f = Law::evaluate(g, pair_params, history[p]);
        local.max_stiffness_over_mass =
            std::max(local.max_stiffness_over_mass, f.stiffness * std::max(inverse_mass_i, inverse_mass[j]));
        force_i -= f.force_on_j;
        torque_i += f.torque_i;
        if constexpr (sum_rule) stiffness_i += f.stiffness;
        if (ghosts && j >= i_end) {
          ghosts->push_back(Ghost{j, f.force_on_j, f.torque_j, f.stiffness});
        } else {
          force[j] += f.force_on_j;
          torque[j] += f.torque_j;
          if constexpr (sum_rule) stiffness[j] += f.stiffness;
        }
        if constexpr (Measure) {
          local.contacts += g.overlap > 0.0;
          local.contact_force_sum += norm(f.force_on_j);
          local.strain_energy += f.energy;
          local.max_overlap_ratio = std::max(local.max_overlap_ratio, g.overlap / rsum);
        }
      }
      force[i] += force_i;
      torque[i] += torque_i;
      if constexpr (sum_rule) stiffness[i] += stiffness_i;
    }
    if (any_bonded)
      std::visit([&](auto& bonds) { bond_forces<typename std::decay_t<decltype(bonds.law)>, Measure>(
                                        bonds, t, force, torque, stiffness, local); },
                 bond_model_);
    if (!walls_.empty()) wall_forces<Law, Measure>(model, t, force, torque, stiffness, local);
    thread_totals_[t] = local;
#pragma omp barrier
    if (owned) {
      // Contributions of earlier threads to this thread's particles, in thread order:
      // deterministic for a fixed thread count.
      for (int s = 0; s < t; ++s)
        for (const Ghost& g : thread_ghosts_[s]) {
          if (g.particle < i_begin || g.particle >= i_end) continue;
          force[g.particle] += g.force;
          torque[g.particle] += g.torque;
          if constexpr (sum_rule) stiffness[g.particle] += g.stiffness;
        }
    } else if (T > 1) {
      // Sum the thread buffers in thread order: deterministic for a fixed thread count.
#pragma omp for schedule(static)
      for (int k = 0; k < n; ++k) {
        Vec3 f{}, m{};
        for (int s = 0; s < T; ++s) {
          f += thread_force_[s][k];
          m += thread_torque_[s][k];
        }
        particles_.force[k] = f;
        particles_.torque[k] = m;
      }
    }
    if constexpr (sum_rule) {
      // The stiffest particle: sum of its contact stiffnesses over its mass (fixed particles
      // have zero inverse mass and drop out). Max is order-independent: deterministic.
      double largest = 0.0;
      if (T == 1 || owned) {
        for (int k = i_begin; k < i_end; ++k) largest = std::max(largest, stiffness[k] * inverse_mass[k]);
      } else {
#pragma omp for schedule(static)
        for (int k = 0; k < n; ++k) {
          double sum = 0.0;
          for (int s = 0; s < T; ++s) sum += thread_stiffness_[s][k];
          largest = std::max(largest, sum * inverse_mass[k]);
        }
      }
      thread_totals_[t].max_stiffness_over_mass = largest;
    }
  }
  for (int t = 0; t < T; ++t) {
    totals.max_stiffness_over_mass = std::max(totals.max_stiffness_over_mass, thread_totals_[t].max_stiffness_over_mass);
    totals.bond_breaks += thread_totals_[t].bond_breaks;
  }
  for (std::size_t m = 0; m < walls_.size(); ++m) {
    Vec3 sum{};
    for (int t = 0; t < T; ++t) sum += thread_wall_force_[t][m];
    wall_force_[m] = sum;
  }
  broken_bonds_ += totals.bond_breaks;
  if (totals.bond_breaks > 0)
    for (int t = 0; t < T; ++t) {
      breaks_.insert(breaks_.end(), thread_breaks_[t].begin(), thread_breaks_[t].end());
      thread_breaks_[t].clear();
    }
  if constexpr (Measure) {
    for (int t = 0; t < T; ++t) {
      totals.contacts += thread_totals_[t].contacts;
      totals.contact_force_sum += thread_totals_[t].contact_force_sum;
      totals.strain_energy += thread_totals_[t].strain_energy;
      totals.max_overlap_ratio = std::max(totals.max_overlap_ratio, thread_totals_[t].max_overlap_ratio);
    }
  }
}

template <bool Measure>
void Engine::integrate(Totals& totals) {
  const int n = static_cast<int>(particles_.size());
  const double dt = dt_;
  auto& P = particles_;
  double kinetic = 0.0, unbalanced = 0.0;
  long free_count = 0;
#pragma omp parallel for num_threads(threads_) schedule(static) reduction(+ : kinetic, unbalanced, free_count)
  for (int i = 0; i < n; ++i) {
    // Fixed particles have zero inverse mass and inertia: they keep zero velocity without a
    // branch, so the loop vectorizes.
    const double alpha = damping_[i];
    const Vec3 f = apply_local_damping(P.force[i], P.velocity[i], alpha);
    const Vec3 m = apply_local_damping(P.torque[i], P.angular_velocity[i], alpha);
    const Vec3 dv = (P.inverse_mass[i] * dt) * f;
    const Vec3 dw = (P.inverse_inertia[i] * dt) * m;
    if constexpr (Measure) {
      if (!P.fixed[i]) {
        const Vec3 v_sync = P.velocity[i] + 0.5 * dv;
        const Vec3 w_sync = P.angular_velocity[i] + 0.5 * dw;
        kinetic += 0.5 * (P.mass[i] * norm2(v_sync) + P.inertia[i] * norm2(w_sync));
        unbalanced += norm(P.force[i]);
        ++free_count;
      }
    }
    P.velocity[i] += dv;
    P.angular_velocity[i] += dw;
    P.position[i] += dt * P.velocity[i];
  }
  if constexpr (Measure) {
    totals.kinetic_energy = kinetic;
    totals.unbalanced_force_sum = unbalanced;
    totals.free_particles = static_cast<std::size_t>(free_count);
  }
}

template <bool Measure>
Engine::Totals Engine::step_impl() {
  if (neighbors_.needs_rebuild(particles_.position, particles_.radius)) refresh_neighbors();
  Totals totals;
  std::visit(
      [&](auto& model) {
        using Law = std::decay_t<decltype(model.law)>;
        if (config_.time_step <= 0.0 && config_.time_step_rule == TimeStepRule::stiffness_sum)
          pair_forces<Law, Measure, true>(model, totals);
        else
          pair_forces<Law, Measure, false>(model, totals);
      },
      model_);
  if (config_.time_step <= 0.0 && config_.time_step_rule != TimeStepRule::global) {
    dt_ = totals.max_stiffness_over_mass > 0.0
              ? std::min(time_step_cap_, config_.time_step_safety / std::sqrt(totals.max_stiffness_over_mass))
              : time_step_cap_;
  }
  integrate<Measure>(totals);
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
  return d;
}

}  // namespace packlab::dem
