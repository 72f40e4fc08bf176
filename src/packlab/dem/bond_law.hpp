// Bond laws: small value types like the contact laws (contact_law.hpp), evaluated in the
// engine's bond loop over the bond list (bonded particles may separate beyond the neighbour
// list's range). A law provides
//   struct Params;                      per bond material
//   using State = ...;                  per-bond history
//   static double stiffness(const Params&, double radius_i, double radius_j, double rest_length);
//   static BondForce evaluate(const ContactGeometry&, const Params&, State&);
// ContactGeometry::overlap is negative when the bonded particles are apart.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "packlab/dem/contact_law.hpp"

namespace packlab::dem {

struct BondForce {
  Vec3 force_on_j;   // [N]
  Vec3 torque_i;     // [N m]
  Vec3 torque_j;     // [N m]
  double energy;     // [J]
  bool failed;       // a breakage criterion was met this step
  bool broken;       // the bond is gone from this step on (the force is then zero)
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

  static double stiffness(const Params& p, double /*radius_i*/, double /*radius_j*/, double /*rest_length*/) {
    return std::max(p.normal_stiffness, p.shear_stiffness);
  }

  static BondForce evaluate(const ContactGeometry& g, const Params& p, State& shear_force) {
    const Vec3& n = g.normal;
    const double normal_force = p.normal_stiffness * g.overlap;  // negative = tension
    Vec3 fs = rotate_into_plane(shear_force, n, g.mean_spin, g.dt);
    const Vec3 vt = g.relative_velocity - dot(g.relative_velocity, n) * n;
    fs -= (p.shear_stiffness * g.dt) * vt;
    BondForce out{};
    out.failed = -normal_force > p.normal_strength || norm2(fs) > p.shear_strength * p.shear_strength;
    out.broken = out.failed;
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

// Elastic solid bond (bpm-inverse-opals eq. 11-17, the parallel-bond model of Potyondy and
// Cundall as in MUSEN): a cylinder of radius R_b = radius_ratio * min(r_i, r_j), cross-section
// A = pi R_b^2, I = pi R_b^4 / 4, J = 2 I, between the particle centres, initial length L0.
//   normal force   F_n = E A (L - L0) / L0                      (eq. 11, pulls when stretched)
//   shear force    F_t = G A xi_t / L0, G = E / (2 (1 + nu))    (eq. 11), xi_t incremental (eq. 12)
//   torsion        dM_n = -G J / L0 dtheta_n,  bending dM_t = -E I / L0 dtheta_t  (relative
//                  rotation increments of j against i)
// The carried vectors turn with the pair (eq. 13-15, first order as for the contacts).
// Failure (eq. 16-17): sigma = |F_n|/A + |M_t| R_b / I >= sigma_max or
// tau = |F_t|/A + |M_n| R_b / J >= tau_max. (The extracted eq. 16/17 pair F_n with "M^n" and I,
// F_t with "M^t" and J; bending makes normal stress through I and torsion shear stress through
// J, which is what is used.) Which bonds the normal criterion (eq. 16) breaks is the named
// option `compressive_breakage`: false (default, as MUSEN's elastic bond, the paper's code,
// whose COMPRESSIVE_BREAK parameter defaults to 0) applies it to stretched bonds only (L > L0),
// so compressed bonds fail by shear (eq. 17) alone; true applies it to every bond, as eq. 16
// reads. A failed bond stays for relaxation_time while its stiffness decays linearly to zero
// (the paper's 1 % per 1e-11 s over 1 ns: 100 steps of 1 % of the initial stiffness), then it
// is removed.
struct ElasticBond {
  static constexpr const char* name = "elastic";
  struct Params {
    double youngs_modulus;       // E_b [Pa]
    double poisson_ratio;        // nu_b [-]
    double normal_strength;      // sigma_max [Pa]
    double shear_strength;       // tau_max [Pa]
    double radius_ratio = 1.0;   // R_b / min(r_i, r_j) [-]
    double relaxation_time = 1e-9;  // [s]
    bool compressive_breakage = false;  // eq. 16 also for compressed bonds (see above)
  };
  struct State {
    Vec3 tangential{};            // xi_t [m]
    Vec3 torsion{};               // M_n on j [N m]
    Vec3 bending{};               // M_t on j [N m]
    double failed_at = -1.0;      // time of failure [s], -1 while intact
  };

  static double bond_radius(const Params& p, double radius_i, double radius_j) {
    return p.radius_ratio * std::min(radius_i, radius_j);
  }
  static double stiffness(const Params& p, double radius_i, double radius_j, double rest_length) {
    const double rb = bond_radius(p, radius_i, radius_j);
    return p.youngs_modulus * std::numbers::pi * rb * rb / rest_length;
  }

  static BondForce evaluate(const ContactGeometry& g, const Params& p, State& s) {
    BondForce out{};
    const double factor = s.failed_at < 0.0 ? 1.0 : 1.0 - (g.time - s.failed_at) / p.relaxation_time;
    if (factor <= 0.0) {
      out.broken = true;
      return out;
    }
    const Vec3& n = g.normal;
    const double rb = bond_radius(p, g.radius_i, g.radius_j);
    const double area = std::numbers::pi * rb * rb;
    const double inertia = 0.25 * std::numbers::pi * rb * rb * rb * rb;
    const double polar = 2.0 * inertia;
    const double shear_modulus = p.youngs_modulus / (2.0 * (1.0 + p.poisson_ratio));
    const double length = g.radius_i + g.radius_j - g.overlap;
    const double l0 = g.rest_length;
    // eq. 11, normal part: positive when stretched, pulling j back towards i.
    const double normal_force = p.youngs_modulus * area * (length - l0) / l0;
    // eq. 12: tangential deformation carried with the pair plus this step's sliding.
    const Vec3 vt = g.relative_velocity - dot(g.relative_velocity, n) * n;
    s.tangential = rotate_into_plane(s.tangential, n, g.mean_spin, g.dt) + g.dt * vt;
    const Vec3 shear_force = (-shear_modulus * area / l0) * s.tangential;
    // Moments from the relative rotation of j against i, torsion along n, bending across it.
    const Vec3 dtheta = g.dt * g.relative_spin;
    const Vec3 dtheta_n = dot(dtheta, n) * n;
    s.torsion = dot(s.torsion, n) * n - (shear_modulus * polar / l0) * dtheta_n;
    s.bending = rotate_into_plane(s.bending, n, g.mean_spin, g.dt) - (p.youngs_modulus * inertia / l0) * (dtheta - dtheta_n);
    if (s.failed_at < 0.0) {
      const double sigma = std::abs(normal_force) / area + norm(s.bending) * rb / inertia;   // eq. 16
      const double tau = norm(shear_force) / area + norm(s.torsion) * rb / polar;           // eq. 17
      if ((sigma >= p.normal_strength && (p.compressive_breakage || length > l0)) || tau >= p.shear_strength) {
        s.failed_at = g.time;
        out.failed = true;
      }
    }
    const double k = s.failed_at < 0.0 ? 1.0 : std::max(0.0, 1.0 - (g.time - s.failed_at) / p.relaxation_time);
    const Vec3 force_t = k * shear_force;
    const Vec3 moment_arm = cross(n, force_t);
    out.force_on_j = (-k * normal_force) * n + force_t;
    out.torque_i = -g.branch_i * moment_arm - k * (s.torsion + s.bending);
    out.torque_j = -g.branch_j * moment_arm + k * (s.torsion + s.bending);
    const double ka = p.youngs_modulus * area / l0, kt = shear_modulus * area / l0;
    out.energy = k * (0.5 * normal_force * normal_force / ka + 0.5 * norm2(shear_force) / kt +
                      0.5 * norm2(s.torsion) / (shear_modulus * polar / l0) +
                      0.5 * norm2(s.bending) / (p.youngs_modulus * inertia / l0));
    return out;
  }
};

}  // namespace packlab::dem
