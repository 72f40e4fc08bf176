// Bond laws: small value types like the contact laws (dem/contact/contact_law.hpp), in one file
// each under dem/bond/ and registered in dem/bond/registry.hpp; evaluated in the engine's bond
// loop over the bond list (bonded particles may separate beyond the neighbour list's range).
// A law provides
//   static constexpr std::string_view name;     the user-facing name ("contact", "elastic")
//   struct Params;                              per bond material, defaults as initializers
//   static const std::array<Parameter<Params>, K> parameters;
//                                               each field declared once (name, unit, range, doc)
//   using State = ...;                          per-bond history
//   static double stiffness(const Params&, double radius_i, double radius_j, double rest_length);
//   static constexpr bool uses_rest_length;     the bond's initial length must be > 0
//   static bool failed(const State&);           failed but still relaxing (its strain is not
//                                               reported)
//   static BondForce evaluate(const ContactGeometry&, const Params&, State&);
// and, for the static solver (mechanics/static_stiffness.hpp),
//   static BondTangent tangent(const ContactGeometry&, const Params&);
//                                               the intact bond's stiffnesses (linear laws:
//                                               exact; others: at the current state)
//   static double failure_ratio(const BondLoad&, const ContactGeometry&, const Params&);
//                                               the largest of (stress / strength) over the
//                                               law's breakage criteria for that load: the
//                                               bond fails when it reaches 1; the criteria must
//                                               be positively homogeneous of degree one in the
//                                               load (scaling the load by s scales the ratio by
//                                               s), which sequential linear analysis relies on
// ContactGeometry::overlap is negative when the bonded particles are apart.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string_view>

#include "packlab/core/parameter.hpp"
#include "packlab/dem/contact/contact_law.hpp"

namespace packlab::dem {

struct BondForce {
  Vec3 force_on_j;   // [N]
  Vec3 torque_i;     // [N m]
  Vec3 torque_j;     // [N m]
  double energy;     // [J]
  bool failed;       // a breakage criterion was met this step
  bool broken;       // the bond is gone from this step on (the force is then zero)
};

// An intact bond linearized (static solver): force on j dF = -normal du_n n - shear du_t for the
// relative displacement du of the contact points, moment on j dM = -torsion dtheta_n - bending
// dtheta_t for the relative rotation dtheta of j against i (n: along the bond, t: across it).
struct BondTangent {
  double normal = 0.0;   // [N/m]
  double shear = 0.0;    // [N/m]
  double torsion = 0.0;  // [N m/rad]
  double bending = 0.0;  // [N m/rad]
};

// What a bond carries, as the breakage criteria read it.
struct BondLoad {
  double normal_force = 0.0;  // positive = tension (the bond stretched) [N]
  double shear_force = 0.0;   // magnitude [N]
  double torsion = 0.0;       // magnitude of the twisting moment [N m]
  double bending = 0.0;       // magnitude of the bending moment [N m]
};

}  // namespace packlab::dem
