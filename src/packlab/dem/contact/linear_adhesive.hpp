#pragma once

#include <algorithm>

#include "packlab/dem/contact/contact_law.hpp"

namespace packlab::dem {

// Linear spring contact with DMT-type adhesion (cohesive powders): the linear law of
// linear.hpp plus a constant attraction F_0 = 2 pi W R* (Derjaguin-Muller-Toporov pull-off
// force, W the work of adhesion, R* = r_i r_j / (r_i + r_j)) while the particles touch, fading
// linearly to zero over the separation `adhesion_range` once they are apart:
//   overlap d >= 0:            F_n = k_n d - F_0
//   -adhesion_range < d < 0:   F_n = -F_0 (1 + d / adhesion_range)
//   d <= -adhesion_range:      F_n = 0
// (positive = repulsive). The force is conservative, U(d) = 1/2 k_n d^2 - F_0 d - F_0 d_r / 2
// touching and -F_0 (d + d_r)^2 / (2 d_r) apart, so an undamped pair conserves energy; the
// largest tension a pair sustains, the pull-off force, is F_0 (at d = 0), and a free pair at
// rest sits at the overlap F_0 / k_n. The shear spring is the linear law's, with the Coulomb
// limit mu k_n d = mu (F_n + F_0) set by the total compressive load (adhesion raises friction);
// it exists only while touching. Mixed types: W_ab = sqrt(W_a W_b) (Berthelot), the range the
// mean of the two.
struct LinearAdhesive {
  static constexpr std::string_view name = "linear_adhesive";
  static constexpr std::array<std::string_view, 5> properties{"normal_stiffness", "shear_stiffness", "friction",
                                                              "work_of_adhesion", "adhesion_range"};
  struct Params {
    double normal_stiffness;  // [N/m]
    double shear_stiffness;   // [N/m]
    double friction;          // [-]
    double work_of_adhesion;  // W [J/m^2]
    double adhesion_range;    // d_r [m]
  };
  using History = Vec3;  // shear force on j [N]

  static Params mix(const Material& a, const Material& b, StiffnessRule rule) {
    return {combine_stiffness(a.normal_stiffness, b.normal_stiffness, rule),
            combine_stiffness(a.shear_stiffness, b.shear_stiffness, rule), std::min(a.friction, b.friction),
            std::sqrt(a.work_of_adhesion * b.work_of_adhesion), 0.5 * (a.adhesion_range + b.adhesion_range)};
  }
  static double reach(const Params& p) { return p.adhesion_range; }
  static double stiffness(const Params& p, double /*radius*/) {
    return std::max(p.normal_stiffness, p.shear_stiffness);
  }
  static double pull_off_force(const Params& p, double radius_i, double radius_j) {
    return 2.0 * std::numbers::pi * p.work_of_adhesion * radius_i * radius_j / (radius_i + radius_j);
  }

  // Both branches (apart, touching) evaluated and selected: no branch (contact_law.hpp).
  static PairForce evaluate(const ContactGeometry& g, const Params& p, History& shear_force) {
    const Vec3& n = g.normal;
    const double f0 = pull_off_force(p, g.radius_i, g.radius_j);
    const double d = g.overlap;
    const bool touching = d >= 0.0;
    // Apart: the fading attraction only.
    const double apart = std::max(0.0, 1.0 + d / p.adhesion_range);
    // Touching: spring, pull-off force, and the shear spring limited by mu k_n d.
    Vec3 fs = rotate_into_plane(shear_force, n, g.mean_spin, g.dt);
    const Vec3 vt = g.relative_velocity - dot(g.relative_velocity, n) * n;
    fs -= (p.shear_stiffness * g.dt) * vt;
    fs *= slip_scale(norm2(fs), p.friction * p.normal_stiffness * d) * static_cast<double>(touching);
    shear_force = fs;
    const double normal_force = touching ? p.normal_stiffness * d - f0 : -f0 * apart;
    const Vec3 moment_arm = cross(n, fs);
    PairForce out;
    out.stiffness = std::max({p.normal_stiffness, p.shear_stiffness, f0 / p.adhesion_range});
    out.force_on_j = normal_force * n + fs;
    out.torque_i = -g.branch_i * moment_arm;
    out.torque_j = -g.branch_j * moment_arm;
    out.normal_force = normal_force;
    out.energy = touching ? 0.5 * p.normal_stiffness * d * d - f0 * d - 0.5 * f0 * p.adhesion_range +
                                0.5 * norm2(fs) * safe_inverse(p.shear_stiffness)
                          : -0.5 * f0 * p.adhesion_range * apart * apart;
    return out;
  }
};

}  // namespace packlab::dem
