// Contact laws: small value types with one call signature (STYLE.md item 2).
//
// A law provides
//   struct Params;                              per pair of particle types, from mix()
//   using History = ...;                        per-contact state carried between steps
//   static Params mix(TypeParams a, TypeParams b, StiffnessRule rule);
//   static double stiffness(const Params&);     for the critical time step
//   static PairForce evaluate(const ContactGeometry&, const Params&, History&);
// The engine instantiates one pair loop per law; adding a law touches no loop.
#pragma once

#include <cmath>

#include "packlab/core/vec3.hpp"
#include "packlab/dem/material.hpp"

namespace packlab::dem {

// What the engine knows about a touching pair at time t.
struct ContactGeometry {
  Vec3 normal;             // unit vector from particle i to particle j
  double overlap;          // r_i + r_j - distance > 0 [m]
  double branch_i;         // distance from centre i to the contact point [m]
  double branch_j;         // distance from centre j to the contact point [m]
  Vec3 relative_velocity;  // velocity of j's contact point relative to i's [m/s]
  Vec3 mean_spin;          // (omega_i + omega_j) / 2 [rad/s]
  double dt;               // time step [s]
};

struct PairForce {
  Vec3 force_on_j;      // the force on i is its negative [N]
  Vec3 torque_i;        // [N m]
  Vec3 torque_j;        // [N m]
  double normal_force;  // magnitude of the normal part (positive = compressive) [N]
  double energy;        // elastic energy stored in the contact [J]
};

// Carries a tangential vector from the last step into the current contact plane: removes its
// component along the new normal (the tilt of the pair) and turns it about the normal by the
// mean spin of the pair (the twist). Both are first-order rotations, as LAMMPS's granular
// history does: the magnitude changes only at second order in the rotation per step
// (~1e-12 relative for typical steps), with no sqrt or division in the pair loop.
inline Vec3 rotate_into_plane(Vec3 tangential, const Vec3& normal, const Vec3& mean_spin, double dt) {
  tangential -= dot(tangential, normal) * normal;
  tangential += (dot(mean_spin, normal) * dt) * cross(normal, tangential);
  return tangential;
}

// Linear spring contact, PFC style (vem-void-expansion-method eq. 1-2,
// doh-elastic-properties §2.1): F_n = k_n U_n; shear force built from increments
// dF_s = -k_s dU_s, rotated with the contact plane, limited by Coulomb |F_s| <= mu F_n.
struct LinearContact {
  static constexpr const char* name = "linear";
  struct Params {
    double normal_stiffness;  // [N/m]
    double shear_stiffness;   // [N/m]
    double friction;          // [-]
  };
  using History = Vec3;  // shear force on j [N]

  static Params mix(const TypeParams& a, const TypeParams& b, StiffnessRule rule) {
    return {combine_stiffness(a.normal_stiffness, b.normal_stiffness, rule),
            combine_stiffness(a.shear_stiffness, b.shear_stiffness, rule), std::min(a.friction, b.friction)};
  }
  static double stiffness(const Params& p) { return std::max(p.normal_stiffness, p.shear_stiffness); }

  static PairForce evaluate(const ContactGeometry& g, const Params& p, History& shear_force) {
    const Vec3& n = g.normal;
    const double normal_force = p.normal_stiffness * g.overlap;  // eq. 1
    Vec3 fs = rotate_into_plane(shear_force, n, g.mean_spin, g.dt);
    const Vec3 vt = g.relative_velocity - dot(g.relative_velocity, n) * n;
    fs -= (p.shear_stiffness * g.dt) * vt;  // eq. 2, dU_s = v_t dt
    const double limit = p.friction * normal_force;
    const double fs2 = norm2(fs);
    if (fs2 > limit * limit) fs *= limit / std::sqrt(fs2);  // Coulomb slip
    shear_force = fs;
    const Vec3 moment_arm = cross(n, fs);
    PairForce out;
    out.force_on_j = normal_force * n + fs;
    out.torque_i = -g.branch_i * moment_arm;
    out.torque_j = -g.branch_j * moment_arm;
    out.normal_force = normal_force;
    out.energy = 0.5 * normal_force * g.overlap +
                 (p.shear_stiffness > 0.0 ? 0.5 * norm2(fs) / p.shear_stiffness : 0.0);
    return out;
  }
};

}  // namespace packlab::dem
