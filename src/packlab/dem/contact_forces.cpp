// The forces at the current state as plain arrays (no step taken) and the per-particle Cauchy
// stress computed from them (bpm-inverse-opals eq. 21).
#include <numbers>

#include "packlab/dem/engine.hpp"

namespace packlab::dem {

ContactGeometry Engine::pair_geometry(std::size_t i, std::size_t j, const Vec3& d, double distance) const {
  const auto& P = particles_;
  ContactGeometry g;
  g.normal = d * (1.0 / distance);
  g.overlap = P.radius[i] + P.radius[j] - distance;
  g.branch_i = P.radius[i] - 0.5 * g.overlap;
  g.branch_j = P.radius[j] - 0.5 * g.overlap;
  g.relative_velocity = P.velocity[j] - P.velocity[i] -
                        cross(g.branch_j * P.angular_velocity[j] + g.branch_i * P.angular_velocity[i], g.normal);
  g.mean_spin = 0.5 * (P.angular_velocity[i] + P.angular_velocity[j]);
  g.dt = dt_;
  g.radius_i = P.radius[i];
  g.radius_j = P.radius[j];
  // Two fixed particles: no relative motion to damp (0, not infinity, so no NaN reaches them).
  const double inverse_sum = P.inverse_mass[i] + P.inverse_mass[j];
  g.effective_mass = inverse_sum > 0.0 ? 1.0 / inverse_sum : 0.0;
  g.spin_i = P.angular_velocity[i];
  g.spin_j = P.angular_velocity[j];
  g.relative_spin = P.angular_velocity[j] - P.angular_velocity[i];
  g.time = time_;
  return g;
}

ContactForces Engine::contact_forces() const {
  ContactForces out;
  const auto& P = particles_;
  const std::size_t n = P.size();
  // The elastic forces as stored: no increment of the histories (dt = 0) and no damping
  // (no relative motion).
  auto as_stored = [](ContactGeometry g) {
    g.dt = 0.0;
    g.relative_velocity = g.mean_spin = g.spin_i = g.spin_j = g.relative_spin = Vec3{};
    return g;
  };
  auto push = [&](int i, int j, int kind, const Vec3& branch, const Vec3& force) {
    out.i.push_back(i);
    out.j.push_back(j);
    out.kind.push_back(kind);
    out.branch.push_back(branch);
    out.force.push_back(force);
  };
  std::visit(
      [&](const auto& model) {
        using Law = std::decay_t<decltype(model.law)>;
        for (std::size_t i = 0; i < n; ++i)
          for (int p = neighbors_.first(static_cast<int>(i)); p < neighbors_.first(static_cast<int>(i) + 1); ++p) {
            if (!pair_bonded_.empty() && pair_bonded_[p]) continue;
            const std::size_t j = static_cast<std::size_t>(neighbors_.partner()[p]);
            const Vec3 d = P.position[j] + neighbors_.image_offset(neighbors_.image()[p]) - P.position[i];
            const auto& params = model.params(P.type[i], P.type[j]);
            const double cutoff = P.radius[i] + P.radius[j] + Law::reach(params);
            if (norm2(d) >= cutoff * cutoff) continue;
            // Runs that keep no pair history (pair_histories_) evaluate as from a fresh one.
            auto history = pair_histories_ ? model.history[p] : typename Law::History{};
            const PairForce f = Law::evaluate(as_stored(pair_geometry(i, j, d, norm(d))), params, history);
            push(original_index_[i], original_index_[j], ContactForces::contact, d, f.force_on_j);
          }
        for (std::size_t m = 0; m < walls_.size(); ++m)
          for (std::size_t k = 0; k < n; ++k) {
            const double distance = dot(P.position[k] - walls_[m].point, walls_[m].normal);
            const auto& params = model.params(P.type[k], P.type[k]);
            if (distance >= P.radius[k] + Law::reach(params)) continue;
            const ContactGeometry g = as_stored(wall_geometry(k, walls_[m], distance));
            auto history = model.wall_history[k * walls_.size() + m];
            const PairForce f = Law::evaluate(g, params, history);
            push(original_index_[k], -1 - static_cast<int>(m), ContactForces::wall, distance * g.normal, f.force_on_j);
          }
      },
      model_);
  // Bonds in the packing's bond order (the engine keeps them by owner).
  std::vector<std::size_t> engine_bond(bonds_.i.size());
  for (std::size_t b = 0; b < engine_bond.size(); ++b) engine_bond[static_cast<std::size_t>(bond_input_index_[b])] = b;
  std::visit(
      [&](const auto& bonds) {
        for (const std::size_t b : engine_bond) {
          if (bonds_.state[b] != 0) continue;
          const std::size_t i = static_cast<std::size_t>(bonds_.i[b]), j = static_cast<std::size_t>(bonds_.j[b]);
          const Vec3 d = bond_vector(b);
          auto history = bonds.history[b];
          ContactGeometry g = as_stored(pair_geometry(i, j, d, norm(d)));
          g.rest_length = bonds_.rest_length[b];
          const BondForce f = bonds.law.evaluate(g, bonds.params(bonds_.material[b]), history);
          push(original_index_[i], original_index_[j], ContactForces::bond, d, f.force_on_j);
        }
      },
      bond_model_);
  return out;
}

std::vector<std::array<double, 9>> particle_stress(const ContactForces& forces, const Packing& packing) {
  std::vector<std::array<double, 9>> stress(packing.size(), std::array<double, 9>{});
  auto add = [&](int particle, const Vec3& l, const Vec3& f, double weight) {
    auto& s = stress[static_cast<std::size_t>(particle)];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) s[3 * a + b] += weight * l[a] * f[b];
  };
  for (std::size_t c = 0; c < forces.size(); ++c) {
    if (forces.j[c] >= 0) {
      add(forces.i[c], forces.branch[c], -forces.force[c], 0.5);  // i: branch to j, force -F
      add(forces.j[c], -forces.branch[c], forces.force[c], 0.5);  // j: branch to i, force F
    } else {
      add(forces.i[c], forces.branch[c], -forces.force[c], 1.0);  // wall: branch to contact point
    }
  }
  for (std::size_t k = 0; k < packing.size(); ++k) {
    const double r = packing.radius[k];
    const double volume = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    for (double& v : stress[k]) v /= volume;
  }
  return stress;
}

}  // namespace packlab::dem
