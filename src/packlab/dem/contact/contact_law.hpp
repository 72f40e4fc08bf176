// Contact laws: small value types with one call signature (STYLE.md item 2), in one file each
// under dem/contact/ and registered in dem/contact/registry.hpp.
//
// A law provides
//   static constexpr std::string_view name;     the user-facing name ("linear")
//   static constexpr std::array<std::string_view, K> properties;
//                                               the Material properties it reads (dem/material.hpp);
//                                               validated for every particle type
//   struct Params;                              per pair of particle types, from mix()
//   using History = ...;                        per-contact state carried between steps
//                                               (value-initialized when a contact starts)
//   static Params mix(const Material& a, const Material& b, StiffnessRule rule);
//   static double reach(const Params&);         how far beyond touching (centre distance
//                                               r_i + r_j + reach) the law still acts [m];
//                                               0 for laws that act only on overlap
//   static double stiffness(const Params&, double radius);  for the global time-step rule
//   static PairForce evaluate(const ContactGeometry&, const Params&, History&);
//                                               called for every listed pair closer than
//                                               r_i + r_j + reach(params); the geometry's
//                                               overlap is negative for a pair apart
// and, optionally (the static solver, mechanics/static_stiffness.hpp, needs it),
//   static PairTangent tangent(const ContactGeometry&, const Params&);
//                                               the normal and tangential stiffness of a
//                                               touching contact linearized at its overlap
//   static bool torque_free(const Params&);      true where the law can exert no torque
//                                               (the integration may then skip the spins)
//   static PairForce evaluate_central(const ContactGeometry&, const Params&);
//                                               where torque_free holds for every pair of
//                                               types: the force from g.normal, g.overlap,
//                                               g.radius_i, g.radius_j and g.dt alone (no
//                                               velocity, spin or history is gathered), the
//                                               same numbers as evaluate() gives there
//   static History reversed(const History&);    the history seen from the other particle
//                                               (required unless History is a Vec3 along
//                                               the pair from i to j, negated by default,
//                                               or empty; see reversed_history below)
// The engine instantiates one pair loop per law; adding a law touches no loop
// (docs/engine.md, "Adding a contact law").
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string_view>
#include <type_traits>

#include "packlab/core/vec3.hpp"
#include "packlab/dem/material.hpp"

namespace packlab::dem {

// What the engine knows about an interacting pair at time t.
struct ContactGeometry {
  Vec3 normal;                  // unit vector from particle i to particle j
  double overlap;               // r_i + r_j - distance [m]: > 0 touching, < 0 apart (bonds, laws with reach)
  double branch_i;              // distance from centre i to the contact point [m]
  double branch_j;              // distance from centre j to the contact point [m]
  Vec3 relative_velocity;       // velocity of j's contact point relative to i's [m/s]
  Vec3 mean_spin;               // (omega_i + omega_j) / 2 [rad/s]
  double dt;                    // time step [s]
  double radius_i = 0.0;        // [m]
  double radius_j = 0.0;        // [m]
  double effective_mass = 0.0;  // m_i m_j / (m_i + m_j) [kg] (m_i alone against a fixed j)
  Vec3 spin_i{}, spin_j{};      // angular velocities [rad/s]
  // Bonds only:
  Vec3 relative_spin{};      // omega_j - omega_i [rad/s]
  double rest_length = 0.0;  // initial bond length [m]
  double time = 0.0;         // simulated time [s]
};

struct PairForce {
  Vec3 force_on_j;      // the force on i is its negative [N]
  Vec3 torque_i;        // [N m]
  Vec3 torque_j;        // [N m]
  double normal_force;  // magnitude of the normal part (positive = compressive) [N]
  double energy;        // elastic energy stored in the contact [J]
  double stiffness;     // current tangent stiffness, for the contacts time-step rule [N/m]
};

// A contact law linearized about the current overlap (sticking, no slip): dF_n = -normal du_n,
// dF_t = -shear du_t for the relative displacement du of the contact points; shear = 0 without
// friction (the Coulomb limit mu F_n is zero: no tangential force).
struct PairTangent {
  double normal = 0.0;  // [N/m]
  double shear = 0.0;   // [N/m]
};

// Carries a tangential vector from the last step into the current contact plane: removes its
// component along the new normal (the tilt of the pair) and turns it about the normal by the
// mean spin of the pair (the twist). Both are first-order rotations, as LAMMPS's granular
// history does: the magnitude changes only at second order in the rotation per step
// (~1e-12 relative for typical steps), with no sqrt or division in the pair loop.
// Branch-free forms for the laws: the engine evaluates them over blocks of pairs in a loop that
// vectorizes only without branches (dem/step.cpp). slip_scale(f2, limit) is the factor that
// brings a force of squared magnitude f2 down to the Coulomb limit (1 while within it);
// safe_inverse(s) is 1 / s for s > 0 and 0 for s == 0 (no division by zero, no branch).
inline double slip_scale(double f2, double limit) {
  return std::min(1.0, limit / std::sqrt(std::max(f2, std::numeric_limits<double>::min())));
}
inline double safe_inverse(double s) {
  return static_cast<double>(s > 0.0) / std::max(s, std::numeric_limits<double>::min());
}

inline Vec3 rotate_into_plane(Vec3 tangential, const Vec3& normal, const Vec3& mean_spin, double dt) {
  tangential -= dot(tangential, normal) * normal;
  tangential += (dot(mean_spin, normal) * dt) * cross(normal, tangential);
  return tangential;
}

// A pair's history seen from its other particle: when the engine renumbers its particles
// (EngineConfig::resort_particles) a pair's i and j can swap. A vector history from i to j (a
// shear force on j, a tangential displacement of j relative to i) is negated; an empty one
// stays; any other needs the law's reversed().
template <class Law>
typename Law::History reversed_history(const typename Law::History& h) {
  using History = typename Law::History;
  if constexpr (requires { Law::reversed(h); })
    return Law::reversed(h);
  else if constexpr (std::is_same_v<History, Vec3>)
    return -h;
  else {
    static_assert(std::is_empty_v<History>, "a contact law with this history must define reversed()");
    return h;
  }
}

}  // namespace packlab::dem
