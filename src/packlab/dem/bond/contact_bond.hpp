#pragma once

#include "packlab/dem/bond/bond_law.hpp"

namespace packlab::dem {

// PFC contact bond (doh-elastic-properties §2.1): the linear contact law continued into
// tension, F_n = k_n U_n with U_n < 0 when apart (eq. 1), incremental shear dF_s = -k_s dU_s
// (eq. 2) without a Coulomb limit (friction is superseded while bonded). It breaks when the
// tension exceeds the normal strength F_nB or the shear force the shear strength F_sB; the
// pair then interacts through the contact law.
struct ContactBond {
  static constexpr std::string_view name = "contact";
  struct Params {
    double normal_stiffness = 1.0e2;  // k_n [N/m]
    double shear_stiffness = 1.0e1;   // k_s [N/m]
    double normal_strength = std::numeric_limits<double>::infinity();  // F_nB [N] (tension)
    double shear_strength = std::numeric_limits<double>::infinity();   // F_sB [N]
  };
  static constexpr std::array<Parameter<Params>, 4> parameters{{
      {"normal_stiffness", "N/m", "Bond normal stiffness k_n", &Params::normal_stiffness, ranges::positive},
      {"shear_stiffness", "N/m", "Bond shear stiffness k_s", &Params::shear_stiffness, ranges::non_negative},
      {"normal_strength", "N", "Tensile strength F_nB", &Params::normal_strength, ranges::non_negative_or_inf},
      {"shear_strength", "N", "Shear strength F_sB", &Params::shear_strength, ranges::non_negative_or_inf},
  }};
  using State = Vec3;  // shear force on j [N]

  static double stiffness(const Params& p, double /*radius_i*/, double /*radius_j*/, double /*rest_length*/) {
    return std::max(p.normal_stiffness, p.shear_stiffness);
  }

  static constexpr bool uses_rest_length = false;  // needs the bond's initial length > 0
  static bool failed(const State& /*s*/) { return false; }

  static BondTangent tangent(const ContactGeometry& /*g*/, const Params& p) {
    return {p.normal_stiffness, p.shear_stiffness, 0.0, 0.0};
  }
  // Tension against F_nB, shear force against F_sB (the criteria of evaluate()).
  static double failure_ratio(const BondLoad& load, const ContactGeometry& /*g*/, const Params& p) {
    // A strength of 0 fails at any load (and 0 / 0 is not a ratio).
    auto ratio = [](double value, double strength) { return value > 0.0 ? value / strength : 0.0; };
    return std::max(ratio(load.normal_force, p.normal_strength), ratio(load.shear_force, p.shear_strength));
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

}  // namespace packlab::dem
