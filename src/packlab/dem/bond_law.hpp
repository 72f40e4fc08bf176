// Bond laws: small value types like the contact laws (contact_law.hpp), evaluated in the
// engine's bond loop over the bond list (bonded particles may separate beyond the neighbour
// list's range). A law provides
//   struct Params;                      per bond material
//   using State = ...;                  per-bond history
//   static double stiffness(const Params&);
//   static BondForce evaluate(const ContactGeometry&, const Params&, State&);
// ContactGeometry::overlap is negative when the bonded particles are apart.
#pragma once

#include "packlab/dem/contact_law.hpp"

namespace packlab::dem {

struct BondForce {
  Vec3 force_on_j;   // [N]
  Vec3 torque_i;     // [N m]
  Vec3 torque_j;     // [N m]
  double energy;     // [J]
  bool broken;       // the bond failed this step (the force is then zero)
};

// PFC contact bond (doh-elastic-properties §2.1): the linear contact law continued into
// tension, F_n = k_n U_n with U_n < 0 when apart (eq. 1), incremental shear dF_s = -k_s dU_s
// (eq. 2) without a Coulomb limit (friction is superseded while bonded). It breaks when the
// tension exceeds the normal strength F_nB or the shear force the shear strength F_sB; the
// pair then interacts through the contact law.
struct ContactBond {
  static constexpr const char* name = "contact";
  struct Params {
    double normal_stiffness;  // k_n [N/m]
    double shear_stiffness;   // k_s [N/m]
    double normal_strength;   // F_nB [N] (tension)
    double shear_strength;    // F_sB [N]
  };
  using State = Vec3;  // shear force on j [N]

  static double stiffness(const Params& p) { return std::max(p.normal_stiffness, p.shear_stiffness); }

  static BondForce evaluate(const ContactGeometry& g, const Params& p, State& shear_force) {
    const Vec3& n = g.normal;
    const double normal_force = p.normal_stiffness * g.overlap;  // negative = tension
    Vec3 fs = rotate_into_plane(shear_force, n, g.mean_spin, g.dt);
    const Vec3 vt = g.relative_velocity - dot(g.relative_velocity, n) * n;
    fs -= (p.shear_stiffness * g.dt) * vt;
    BondForce out{};
    out.broken = -normal_force > p.normal_strength || norm2(fs) > p.shear_strength * p.shear_strength;
    if (out.broken) {
      shear_force = Vec3{};
      return out;
    }
    shear_force = fs;
    const Vec3 moment_arm = cross(n, fs);
    out.force_on_j = normal_force * n + fs;
    out.torque_i = -g.branch_i * moment_arm;
    out.torque_j = -g.branch_j * moment_arm;
    out.energy = 0.5 * normal_force * g.overlap +
                 (p.shear_stiffness > 0.0 ? 0.5 * norm2(fs) / p.shear_stiffness : 0.0);
    return out;
  }
};

}  // namespace packlab::dem
