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

}  // namespace packlab::dem
