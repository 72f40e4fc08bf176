#pragma once

#include <algorithm>

#include "packlab/dem/contact/contact_law.hpp"

namespace packlab::dem {

// Hertz-Mindlin contact with restitution-based damping (bpm-inverse-opals eq. 5-10, as MUSEN):
//   F_n = 4/3 E* sqrt(R*) xi_n^3/2 - 2 sqrt(5/6) beta sqrt(S_n m*) v_n,  S_n = 2 E* sqrt(R* xi_n)
//   F_t = -S_t xi_t - 2 sqrt(5/6) beta sqrt(S_t m*) v_t,                S_t = 8 G* sqrt(R* xi_n)
// with beta = ln(e) / sqrt(pi^2 + ln^2 e) (eq. 7; 1.83 = 2 sqrt(5/6) in eq. 5, 3.66 in eq. 6),
// the tangential overlap xi_t carried into the contact plane each step, and the slip condition
// |F_t,el| <= mu |F_n| (eq. 9) rescaling xi_t (eq. 10). The extraction of eq. 5/6 lost R* under
// the damping root and printed xi_n^3 in eq. 6; the standard forms (eq. 8 and Tsuji et al.)
// are used. The normal force is not allowed to become attractive (damping at separation).
// Rolling resistance: a torque -mu_r |F_n| r_k omega_k/|omega_k| on each particle k (MUSEN's
// constant directional torque).
struct HertzMindlin {
  static constexpr std::string_view name = "hertz_mindlin";
  static constexpr std::array<std::string_view, 5> properties{"youngs_modulus", "poisson_ratio", "restitution",
                                                              "friction", "rolling_friction"};
  struct Params {
    double effective_youngs_modulus;  // E* [Pa]
    double effective_shear_modulus;   // G* [Pa]
    double friction;                  // mu_sl [-]
    double damping_beta;              // ln(e) / sqrt(pi^2 + ln^2 e) [-] (<= 0)
    double rolling_friction;          // mu_r [-]
  };
  using History = Vec3;  // tangential overlap xi_t [m]

  static Params mix(const Material& a, const Material& b, StiffnessRule /*rule*/) {
    const double inv_e = (1 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus +
                         (1 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus;
    const double inv_g = 2 * (2 - a.poisson_ratio) * (1 + a.poisson_ratio) / a.youngs_modulus +
                         2 * (2 - b.poisson_ratio) * (1 + b.poisson_ratio) / b.youngs_modulus;
    const double e = std::min(a.restitution, b.restitution);
    const double log_e = std::log(e);
    return {1.0 / inv_e, 1.0 / inv_g, std::min(a.friction, b.friction),
            log_e / std::sqrt(std::numbers::pi * std::numbers::pi + log_e * log_e),
            std::min(a.rolling_friction, b.rolling_friction)};
  }
  static constexpr double reach(const Params& /*p*/) { return 0.0; }
  // For the global time-step rule: the normal stiffness S_n at an overlap of 1 % of the radius
  // (set --time-step for other regimes).
  static double stiffness(const Params& p, double radius) {
    const double r_eff = 0.5 * radius;
    return 2.0 * p.effective_youngs_modulus * std::sqrt(r_eff * 0.01 * radius);
  }

  // S_n and S_t at the current overlap (the tangent of F_n = 4/3 E* sqrt(R*) delta^3/2; the
  // tangential spring sticking below the Coulomb limit, and zero without friction, where the
  // contact carries no tangential force at all).
  static PairTangent tangent(const ContactGeometry& g, const Params& p) {
    const double r_eff = g.radius_i * g.radius_j / (g.radius_i + g.radius_j);
    const double root = std::sqrt(r_eff * std::max(0.0, g.overlap));
    return {2.0 * p.effective_youngs_modulus * root, p.friction > 0.0 ? 8.0 * p.effective_shear_modulus * root : 0.0};
  }

  static PairForce evaluate(const ContactGeometry& g, const Params& p, History& tangential_overlap) {
    const Vec3& n = g.normal;
    const double r_eff = g.radius_i * g.radius_j / (g.radius_i + g.radius_j);
    const double root = std::sqrt(r_eff * g.overlap);
    const double normal_stiffness = 2.0 * p.effective_youngs_modulus * root;     // S_n
    const double tangential_stiffness = 8.0 * p.effective_shear_modulus * root;  // S_t
    const double damping_factor = -2.0 * std::sqrt(5.0 / 6.0) * p.damping_beta;  // >= 0
    const double vn = dot(g.relative_velocity, n);
    const Vec3 vt = g.relative_velocity - vn * n;
    // eq. 5; v_n < 0 while approaching, so the damping pushes j away then.
    const double elastic_normal = 4.0 / 3.0 * p.effective_youngs_modulus * root * g.overlap;
    const double normal_force =
        std::max(0.0, elastic_normal - damping_factor * std::sqrt(normal_stiffness * g.effective_mass) * vn);
    // eq. 8-10: update the tangential overlap, limit the elastic force by slip.
    Vec3 xi = rotate_into_plane(tangential_overlap, n, g.mean_spin, g.dt) + g.dt * vt;
    Vec3 elastic_tangential = -tangential_stiffness * xi;
    const double scale = slip_scale(norm2(elastic_tangential), p.friction * normal_force);
    elastic_tangential *= scale;
    // Slip: the overlap that gives the limited force (xi scaled alike; S_t > 0 while touching).
    xi *= scale;
    tangential_overlap = xi;
    const Vec3 ft =
        elastic_tangential - (damping_factor * std::sqrt(tangential_stiffness * g.effective_mass)) * vt;  // eq. 6
    const Vec3 moment_arm = cross(n, ft);
    PairForce out;
    out.force_on_j = normal_force * n + ft;
    out.torque_i = -g.branch_i * moment_arm;
    out.torque_j = -g.branch_j * moment_arm;
    // Rolling resistance against each particle's own spin.
    const double rolling = p.rolling_friction * normal_force;
    out.torque_i -= (rolling * g.radius_i * safe_inverse(norm(g.spin_i))) * g.spin_i;
    out.torque_j -= (rolling * g.radius_j * safe_inverse(norm(g.spin_j))) * g.spin_j;
    out.normal_force = normal_force;
    out.energy =
        8.0 / 15.0 * p.effective_youngs_modulus * root * g.overlap * g.overlap + 0.5 * tangential_stiffness * norm2(xi);
    out.stiffness = std::max(normal_stiffness, tangential_stiffness);
    return out;
  }
};

}  // namespace packlab::dem
