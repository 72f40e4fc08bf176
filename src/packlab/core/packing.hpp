// The one shared data type (DESIGN.md): a box and, per particle, position, radius and type,
// with optional velocity, angular velocity, density, fixed flag and extra named scalar
// fields; a bonded model adds a bond list. Plain structs of arrays; every stage reads and
// writes these through io/.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "packlab/core/box.hpp"
#include "packlab/core/vec3.hpp"

namespace packlab {

// Particle types used by the generators; files may carry any non-negative integer.
namespace particle_type {
inline constexpr int structural = 0;
inline constexpr int void_particle = 1;
inline constexpr int pore = 2;
inline constexpr int coating = 3;
inline constexpr int substrate = 4;
}  // namespace particle_type

// Bond list as parallel arrays. `image` is the periodic image of j bonded to i:
// the bond vector is r_j + image*L - r_i.
struct Bonds {
  std::vector<int> i, j;
  std::vector<std::array<int, 3>> image;
  std::vector<int> material;
  std::vector<double> rest_length;  // [m]
  std::vector<int> state;           // 0 intact, 1 broken (kept while it relaxes)

  std::size_t size() const { return i.size(); }
  bool empty() const { return i.empty(); }
  void add(int bi, int bj, std::array<int, 3> bimage, int bmaterial, double brest, int bstate = 0) {
    i.push_back(bi);
    j.push_back(bj);
    image.push_back(bimage);
    material.push_back(bmaterial);
    rest_length.push_back(brest);
    state.push_back(bstate);
  }
};

struct ScalarField {
  std::string name;
  std::vector<double> values;
};

struct Packing {
  Box box;
  std::vector<Vec3> position;          // [m]
  std::vector<double> radius;          // [m]
  std::vector<int> type;               // size N
  std::vector<Vec3> velocity;          // empty or N [m/s]
  std::vector<Vec3> angular_velocity;  // empty or N [rad/s]
  std::vector<double> density;         // empty or N [kg/m^3]
  std::vector<std::uint8_t> fixed;     // empty or N (1 = does not move)
  std::vector<ScalarField> fields;     // extra per-particle scalars (stress, CN, ...)
  Bonds bonds;

  std::size_t size() const { return position.size(); }

  void add(const Vec3& p, double r, int t = particle_type::structural) {
    position.push_back(p);
    radius.push_back(r);
    type.push_back(t);
  }

  // Sum of sphere volumes over the box volume (overlaps counted twice).
  double volume_fraction() const;

  // Throws InputError naming the first inconsistency: array sizes, a box that is not finite
  // or not positive, a non-finite position, velocity or angular velocity, a radius or density
  // that is not positive and finite, a negative type, and validate_bonds(). Extra fields may
  // hold anything (NaN marks a missing value).
  void validate() const;
  // Bond indices in range, no bond of a particle to itself (image 0 0 0; a bond to its own
  // periodic image is allowed), no pair bonded twice (i, j, s and j, i, -s count as the same
  // bond), rest lengths finite and >= 0.
  void validate_bonds() const;

  const ScalarField* field(const std::string& name) const;
  ScalarField& field_or_add(const std::string& name);
};

}  // namespace packlab
