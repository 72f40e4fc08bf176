#pragma once

#include <algorithm>
#include <cmath>

#include "packlab/dem/contact/contact_law.hpp"

namespace packlab::dem {

// DLVO pair law (Derjaguin-Landau-Verwey-Overbeek; doh-elastic-properties §2.2 and its refs
// [11, 28, 29]): the central, conservative interaction of two charged colloidal spheres in an
// electrolyte, a function of the surface separation h = d - r_i - r_j only:
//
//   van der Waals (Hamaker 1937, exact for two spheres of radii a_1, a_2 at centre distance r):
//     U_A = -A/6 [ 2 a_1 a_2 / (r^2 - (a_1 + a_2)^2) + 2 a_1 a_2 / (r^2 - (a_1 - a_2)^2)
//                  + ln((r^2 - (a_1 + a_2)^2) / (r^2 - (a_1 - a_2)^2)) ]
//     (equal spheres: -A/6 [2a^2/(r^2 - 4a^2) + 2a^2/r^2 + ln((r^2 - 4a^2)/r^2)]);
//   electrostatic double layer at constant surface potential, Derjaguin's approximation with
//   the linearized Poisson-Boltzmann equation (Hogg, Healy & Fuerstenau 1966, "HHF"):
//     U_R = pi eps_r eps_0 a_1 a_2/(a_1 + a_2) [ (psi_1 + psi_2)^2 ln(1 + exp(-kappa h))
//                                               + (psi_1 - psi_2)^2 ln(1 - exp(-kappa h)) ]
//     (equal spheres: 2 pi eps_r eps_0 a psi_0^2 ln(1 + exp(-kappa h))), kappa = 1/debye_length.
//
// U_A diverges at contact, so below the separation `dlvo_min_separation` (h_min) the DLVO force
// is held at its value at h_min (the energy continued linearly), and overlapping spheres
// (h < 0) are pushed apart by a linear spring k_n (`normal_stiffness`): the short-range
// repulsion at contact (Born repulsion in the refs' words) as a stiff spring. Beyond
// `dlvo_cutoff` (a separation) the law is zero; the stored energy is shifted by U(h_cutoff) so
// that it is continuous there (force = -dU/dh everywhere else, tested). No tangential force:
// Brownian-dynamics coagulation (generate/brownian_dynamics.hpp) moves spheres without
// rotation, and bonds, not friction, make aggregates stiff.
//
// Mixed types: A_ab = sqrt(A_a A_b), each sphere keeps its own surface potential (the HHF form
// above is for unequal potentials), the mean Debye length, permittivity, h_min and cutoff.
struct Dlvo {
  static constexpr std::string_view name = "dlvo";
  static constexpr std::array<std::string_view, 7> properties{
      "normal_stiffness",      "hamaker_constant",    "surface_potential", "debye_length",
      "relative_permittivity", "dlvo_min_separation", "dlvo_cutoff"};
  static constexpr double vacuum_permittivity = 8.8541878128e-12;  // eps_0 [F/m] (CODATA 2018)

  struct Params {
    double normal_stiffness;       // contact repulsion k_n [N/m]
    double hamaker_constant;       // A [J]
    double potential_i;            // psi of the first type [V]
    double potential_j;            // psi of the second type [V]
    double debye_length;           // 1/kappa [m]
    double relative_permittivity;  // eps_r [-]
    double min_separation;         // h_min [m]
    double cutoff;                 // h_cutoff [m]
  };
  struct History {};  // none: the law is central and conservative

  static Params mix(const Material& a, const Material& b, StiffnessRule rule) {
    return {combine_stiffness(a.normal_stiffness, b.normal_stiffness, rule),
            std::sqrt(a.hamaker_constant * b.hamaker_constant),
            a.surface_potential,
            b.surface_potential,
            0.5 * (a.debye_length + b.debye_length),
            0.5 * (a.relative_permittivity + b.relative_permittivity),
            0.5 * (a.dlvo_min_separation + b.dlvo_min_separation),
            0.5 * (a.dlvo_cutoff + b.dlvo_cutoff)};
  }
  static double reach(const Params& p) { return p.cutoff; }

  // U(h) [J] and F(h) = -dU/dh [N] (positive = repulsive) of the two terms, without the
  // cut-offs: the analytic expressions above, for h > 0. r^2 - (a_1 + a_2)^2 is written
  // h (h + 2 (a_1 + a_2)) so that it keeps its digits near contact.
  struct Value {
    double energy;
    double force;
  };
  static Value van_der_waals(const Params& p, double a1, double a2, double h) {
    const double s = a1 + a2, t = a1 - a2, r = s + h;
    const double p2 = 2.0 * a1 * a2;
    const double near = h * (h + 2.0 * s);  // r^2 - s^2
    const double far = r * r - t * t;       // r^2 - t^2
    const double energy = -p.hamaker_constant / 6.0 * (p2 / near + p2 / far + std::log(near / far));
    // dU/dr = -A/6 [ -2 p2 r / near^2 - 2 p2 r / far^2 + 2 r / near - 2 r / far ], F = -dU/dr.
    return {energy, van_der_waals_force(p, a1, a2, h)};
  }
  static Value double_layer(const Params& p, double a1, double a2, double h) {
    // Uncharged surfaces (psi_0 = 0, a paper case): both terms are +0 (what the formulas give
    // for h > 0), without the exponential.
    if (p.potential_i == 0.0 && p.potential_j == 0.0) return {0.0, 0.0};
    const double kappa = 1.0 / p.debye_length;
    const double x = std::exp(-kappa * h);
    const double prefactor = std::numbers::pi * p.relative_permittivity * vacuum_permittivity * a1 * a2 / (a1 + a2);
    const double plus = (p.potential_i + p.potential_j) * (p.potential_i + p.potential_j);
    const double minus = (p.potential_i - p.potential_j) * (p.potential_i - p.potential_j);
    const double energy = prefactor * (plus * std::log1p(x) + (minus > 0.0 ? minus * std::log1p(-x) : 0.0));
    const double force = prefactor * kappa * x * (plus / (1.0 + x) - (minus > 0.0 ? minus / (1.0 - x) : 0.0));
    return {energy, force};
  }
  // The DLVO interaction at separation h > 0 without the cut-offs: U_A + U_R and its force.
  static Value potential(const Params& p, double a1, double a2, double h) {
    const Value a = van_der_waals(p, a1, a2, h), r = double_layer(p, a1, a2, h);
    return {a.energy + r.energy, a.force + r.force};
  }
  // The law as evaluated (h_min, contact spring, cut-off and energy shift), for any h.
  static Value interaction(const Params& p, double a1, double a2, double h) {
    if (h >= p.cutoff) return {0.0, 0.0};
    const double shift = potential(p, a1, a2, p.cutoff).energy;
    const double hc = std::max(h, p.min_separation);
    const Value v = potential(p, a1, a2, hc);
    Value out{v.energy - shift, v.force};
    if (h < p.min_separation) out.energy += v.force * (p.min_separation - h);  // U continued with slope -F
    if (h < 0.0) {
      out.force += p.normal_stiffness * (-h);
      out.energy += 0.5 * p.normal_stiffness * h * h;
    }
    return out;
  }

  // The force of interaction() alone (no energy, no shift): for loops that need only forces.
  static double interaction_force(const Params& p, double a1, double a2, double h) {
    if (h >= p.cutoff) return 0.0;
    const double hc = std::max(h, p.min_separation);
    return van_der_waals_force(p, a1, a2, hc) + double_layer(p, a1, a2, hc).force +
           p.normal_stiffness * std::max(0.0, -h);
  }
  static double van_der_waals_force(const Params& p, double a1, double a2, double h) {
    const double s = a1 + a2, t = a1 - a2, r = s + h;
    const double p2 = 2.0 * a1 * a2;
    const double near = h * (h + 2.0 * s), far = r * r - t * t;
    return p.hamaker_constant / 3.0 * r * (-p2 / (near * near) - p2 / (far * far) + 1.0 / near - 1.0 / far);
  }

  static double stiffness(const Params& p, double radius) {
    // The steepest part of the law: the van der Waals force's slope at h_min, about
    // A R* / (3 h_min^3) with R* = radius / 2, and the contact spring.
    const double h = p.min_separation;
    return p.normal_stiffness + p.hamaker_constant * 0.5 * radius / (3.0 * h * h * h);
  }

  static PairForce evaluate(const ContactGeometry& g, const Params& p, History& /*history*/) {
    const double h = -g.overlap;
    const Value v = interaction(p, g.radius_i, g.radius_j, h);
    PairForce out;
    out.force_on_j = v.force * g.normal;
    out.torque_i = Vec3{};
    out.torque_j = Vec3{};
    out.normal_force = v.force;
    out.energy = v.energy;
    out.stiffness = stiffness(p, std::min(g.radius_i, g.radius_j));
    return out;
  }
};

}  // namespace packlab::dem
