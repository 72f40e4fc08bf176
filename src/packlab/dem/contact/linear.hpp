#pragma once

#include "packlab/dem/contact/contact_law.hpp"

namespace packlab::dem {

// Linear spring contact, PFC style (vem-void-expansion-method eq. 1-2,
// doh-elastic-properties §2.1): F_n = k_n U_n; shear force built from increments
// dF_s = -k_s dU_s, rotated with the contact plane, limited by Coulomb |F_s| <= mu F_n.
struct LinearContact {
  static constexpr std::string_view name = "linear";
  static constexpr std::array<std::string_view, 3> properties{"normal_stiffness", "shear_stiffness", "friction"};
  struct Params {
    double normal_stiffness;  // [N/m]
    double shear_stiffness;   // [N/m]
    double friction;          // [-]
  };
  using History = Vec3;  // shear force on j [N]

  static Params mix(const Material& a, const Material& b, StiffnessRule rule) {
    return {combine_stiffness(a.normal_stiffness, b.normal_stiffness, rule),
            combine_stiffness(a.shear_stiffness, b.shear_stiffness, rule), std::min(a.friction, b.friction)};
  }
  static constexpr double reach(const Params& /*p*/) { return 0.0; }
  // Without friction the Coulomb limit is zero: no shear force, so no torque, ever.
  static constexpr bool torque_free(const Params& p) { return p.friction == 0.0; }
  static double stiffness(const Params& p, double /*radius*/) {
    return std::max(p.normal_stiffness, p.shear_stiffness);
  }

  // The shear spring sticks below friction x F_n (eq. 2 and the Coulomb slip below): the tangent
  // of a contact about its unslipped state, except without friction, where the limit is zero and
  // the contact carries no shear force at all.
  static PairTangent tangent(const ContactGeometry& /*g*/, const Params& p) {
    return {p.normal_stiffness, p.friction > 0.0 ? p.shear_stiffness : 0.0};
  }

  // Without friction (torque_free): eq. 1 alone. evaluate() gives the same numbers there: its
  // shear force is scaled to the Coulomb limit, zero, and adds a zero to the force and energy.
  static PairForce evaluate_central(const ContactGeometry& g, const Params& p) {
    const double normal_force = p.normal_stiffness * g.overlap;  // eq. 1
    PairForce out{};  // no torque
    out.force_on_j = normal_force * g.normal;
    out.normal_force = normal_force;
    out.energy = 0.5 * normal_force * g.overlap;
    out.stiffness = std::max(p.normal_stiffness, p.shear_stiffness);
    return out;
  }

  static PairForce evaluate(const ContactGeometry& g, const Params& p, History& shear_force) {
    const Vec3& n = g.normal;
    const double normal_force = p.normal_stiffness * g.overlap;  // eq. 1
    Vec3 fs = rotate_into_plane(shear_force, n, g.mean_spin, g.dt);
    const Vec3 vt = g.relative_velocity - dot(g.relative_velocity, n) * n;
    fs -= (p.shear_stiffness * g.dt) * vt;                   // eq. 2, dU_s = v_t dt
    fs *= slip_scale(norm2(fs), p.friction * normal_force);  // Coulomb slip
    shear_force = fs;
    const Vec3 moment_arm = cross(n, fs);
    PairForce out;
    out.force_on_j = normal_force * n + fs;
    out.torque_i = -g.branch_i * moment_arm;
    out.torque_j = -g.branch_j * moment_arm;
    out.normal_force = normal_force;
    out.energy = 0.5 * normal_force * g.overlap + 0.5 * norm2(fs) * safe_inverse(p.shear_stiffness);
    out.stiffness = std::max(p.normal_stiffness, p.shear_stiffness);
    return out;
  }
};

}  // namespace packlab::dem
