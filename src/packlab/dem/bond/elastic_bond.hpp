#pragma once

#include "packlab/dem/bond/bond_law.hpp"

namespace packlab::dem {

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
  static constexpr std::string_view name = "elastic";
  struct Params {
    double youngs_modulus = 0.0;                                       // E_b [Pa] (must be given)
    double poisson_ratio = 0.25;                                       // nu_b [-]
    double normal_strength = std::numeric_limits<double>::infinity();  // sigma_max [Pa]
    double shear_strength = std::numeric_limits<double>::infinity();   // tau_max [Pa]
    double radius_ratio = 1.0;                                         // R_b / min(r_i, r_j) [-]
    double relaxation_time = 1e-9;                                     // [s]
    bool compressive_breakage = false;                                 // eq. 16 also for compressed bonds (see above)
  };
  static constexpr std::array<Parameter<Params>, 7> parameters{{
      {"youngs_modulus", "Pa", "Bond Young's modulus E_b", &Params::youngs_modulus, ranges::positive},
      {"poisson_ratio", "", "Bond Poisson's ratio nu_b", &Params::poisson_ratio, Range{-1.0, 0.5, true, true}},
      {"normal_strength", "Pa", "Normal strength sigma_max (eq. 16)", &Params::normal_strength,
       ranges::positive_or_inf},
      {"shear_strength", "Pa", "Shear strength tau_max (eq. 17)", &Params::shear_strength, ranges::positive_or_inf},
      {"radius_ratio", "", "Bond radius R_b / min(r_i, r_j)", &Params::radius_ratio, Range{0.0, 1.0, true, false}},
      {"relaxation_time", "s", "Time over which a failed bond's stiffness decays to zero", &Params::relaxation_time,
       ranges::positive},
      {"compressive_breakage", "", "Apply eq. 16 to compressed bonds too (MUSEN: only to stretched ones)",
       &Params::compressive_breakage},
  }};
  struct State {
    Vec3 tangential{};        // xi_t [m]
    double torsion = 0.0;     // M_n on j along the bond axis n [N m] (a scalar: always along n)
    Vec3 bending{};           // M_t on j [N m]
    double failed_at = -1.0;  // time of failure [s], -1 while intact
  };

  static double bond_radius(const Params& p, double radius_i, double radius_j) {
    return p.radius_ratio * std::min(radius_i, radius_j);
  }
  static double stiffness(const Params& p, double radius_i, double radius_j, double rest_length) {
    const double rb = bond_radius(p, radius_i, radius_j);
    return p.youngs_modulus * std::numbers::pi * rb * rb / rest_length;
  }

  static constexpr bool uses_rest_length = true;  // needs the bond's initial length > 0
  static bool failed(const State& s) { return s.failed_at >= 0.0; }

  // eq. 11 and the moment increments: E A / L0, G A / L0, G J / L0, E I / L0.
  static BondTangent tangent(const ContactGeometry& g, const Params& p) {
    const double rb = bond_radius(p, g.radius_i, g.radius_j);
    const double area = std::numbers::pi * rb * rb;
    const double inertia = 0.25 * area * rb * rb;
    const double shear_modulus = p.youngs_modulus / (2.0 * (1.0 + p.poisson_ratio));
    const double l0 = g.rest_length;
    return {p.youngs_modulus * area / l0, shear_modulus * area / l0, shear_modulus * 2.0 * inertia / l0,
            p.youngs_modulus * inertia / l0};
  }
  // eq. 16 (for stretched bonds only unless compressive_breakage) and eq. 17, as in evaluate().
  static double failure_ratio(const BondLoad& load, const ContactGeometry& g, const Params& p) {
    const double rb = bond_radius(p, g.radius_i, g.radius_j);
    const double area = std::numbers::pi * rb * rb;
    const double inertia = 0.25 * area * rb * rb;
    const double sigma = std::abs(load.normal_force) / area + load.bending * rb / inertia;
    const double tau = load.shear_force / area + load.torsion * rb / (2.0 * inertia);
    const bool normal_applies = p.compressive_breakage || load.normal_force > 0.0;
    return std::max(normal_applies ? sigma / p.normal_strength : 0.0, tau / p.shear_strength);
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
    const double dtheta_along_n = dot(dtheta, n);
    const Vec3 dtheta_n = dtheta_along_n * n;
    // Torsion is the moment's component along the current axis, so it is carried as a number
    // (issue #14: 16 bytes per bond less than a vector, which turning with n only projected).
    s.torsion -= (shear_modulus * polar / l0) * dtheta_along_n;
    s.bending =
        rotate_into_plane(s.bending, n, g.mean_spin, g.dt) - (p.youngs_modulus * inertia / l0) * (dtheta - dtheta_n);
    if (s.failed_at < 0.0) {
      const double sigma = std::abs(normal_force) / area + norm(s.bending) * rb / inertia;  // eq. 16
      const double tau = norm(shear_force) / area + std::abs(s.torsion) * rb / polar;       // eq. 17
      if ((sigma >= p.normal_strength && (p.compressive_breakage || length > l0)) || tau >= p.shear_strength) {
        s.failed_at = g.time;
        out.failed = true;
      }
    }
    const double k = s.failed_at < 0.0 ? 1.0 : std::max(0.0, 1.0 - (g.time - s.failed_at) / p.relaxation_time);
    const Vec3 force_t = k * shear_force;
    const Vec3 moment_arm = cross(n, force_t);
    out.force_on_j = (-k * normal_force) * n + force_t;
    const Vec3 moment = s.torsion * n + s.bending;
    out.torque_i = -g.branch_i * moment_arm - k * moment;
    out.torque_j = -g.branch_j * moment_arm + k * moment;
    const double ka = p.youngs_modulus * area / l0, kt = shear_modulus * area / l0;
    out.energy = k * (0.5 * normal_force * normal_force / ka + 0.5 * norm2(shear_force) / kt +
                      0.5 * s.torsion * s.torsion / (shear_modulus * polar / l0) +
                      0.5 * norm2(s.bending) / (p.youngs_modulus * inertia / l0));
    return out;
  }
};

}  // namespace packlab::dem
