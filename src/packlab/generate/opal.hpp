// Inverse-opal builder (bpm-inverse-opals §2.1, §4): from a packing of primary
// particles and a set of spherical pores, a bonded-particle model of a (coated) inverse opal on
// a fixed substrate.
//
// Steps, in order (every choice is a named option below):
//  1. Pores: an FCC lattice of pores of diameter D with [111] or [100] along z, or a given list
//     of pores (e.g. random pores: a force-biased packing of pore-sized spheres, §4).
//  2. Pore test, eq. (1): particle p lies in pore k when
//        L = |X_k - X_p| <= R_k + R_p            (minimum image along periodic axes).
//  3. Coating (L_coat > 0), eq. (2): p is a coating candidate when it lies in a pore (1) and,
//     for every pore k it lies in, R_k + R_p - L_coat <= L  (within L_coat of that pore's
//     surface, never deeper inside any pore). Interpore openings are kept free: a candidate is
//     kept as coating only when it lies within L_coat + R_p of the silica surface, i.e. when
//     some remaining structural particle s (one not in any pore) has |X_s - X_p| - R_s <=
//     L_coat + R_p ("opening_distance"). Candidates in an opening are far from any silica.
//     Kept candidates become particle_type::coating (titania); every other particle in a pore
//     is removed ("all particles that satisfy (1) but not (2) are cut out").
//  4. Substrate: the remaining particles whose centre lies below z_bottom + layers x d_mean
//     (z_bottom = lowest particle bottom, min(z_p - R_p); d_mean = mean input diameter; two
//     layers by default) become particle_type::substrate with Packing::fixed = 1; all other
//     particles get fixed = 0. Substrate particles that were coating become substrate.
//  5. Bonds between every pair with centre distance < bond_cutoff_ratio x (R_i + R_j)
//     (= 1.75 d for equal particles), across periodic boundaries (generate::add_bonds: image
//     shift and rest length = image distance stored per bond).
//
// Bond materials (§2.1): "silica bonds between silica particles and between silica and a fixed
// layer; titania bonds between titania particles, titania and silica, and titania and a fixed
// layer" (the titania–silica interface is not resolved and takes titania's properties):
//     silica–silica, silica–substrate         -> opal_bond_material::silica
//     titania–{titania, silica, substrate}    -> opal_bond_material::titania
//     substrate–substrate                     -> opal_bond_material::substrate
// The paper does not say how substrate particles bond to each other; both ends are fixed, so
// such bonds carry no load in a test. They are kept (material `substrate`) so the model stays
// one connected body in files and viewers; a test may give them any stiffness.
//
// Units: SI (lengths in m, densities in kg/m^3). Box: the particle packing's box; the pores use
// the same periodic axes (minimum image). Sizes: the paper uses 15 nm particles and 762 nm
// pores (ratio ~51); the ratio is free here (tests and the demo use 8-12).
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "packlab/core/packing.hpp"
#include "packlab/core/random.hpp"

namespace packlab::generate {

// Material index of each bond in the built model (Packing::bonds.material).
namespace opal_bond_material {
inline constexpr int silica = 0;     // silica–silica, silica–substrate
inline constexpr int titania = 1;    // titania–titania, titania–silica, titania–substrate
inline constexpr int substrate = 2;  // substrate–substrate (both ends fixed)
}  // namespace opal_bond_material

// Bond material of two particle types by the rules above; -1 (no bond) for any other type
// (e.g. a pore or void particle left in the input).
int opal_bond_material_of(int type_i, int type_j);

// Orientation of the FCC pore lattice: which crystal direction lies along z.
enum class FccOrientation { z111, z100 };
std::string fcc_orientation_name(FccOrientation o);            // "111", "100"
FccOrientation fcc_orientation_from_name(const std::string&);  // InputError naming the key

// FCC lattice of pores of equal diameter.
struct FccPores {
  double diameter = 0.0;  // pore diameter D [m], > 0
  FccOrientation orientation = FccOrientation::z111;
  // Nearest-neighbour distance between pore centres / D, in [0.5, 2]: 1 = touching pores
  // (pore volume fraction 0.7405, the paper's 74 %); < 1 overlapping pores (wider openings,
  // the "neck"); > 1 separated (closed) pores.
  double spacing_ratio = 1.0;
  // A lattice point [m]. Default (auto): x, y at the box's lo corner; z such that the lowest
  // pore layer clears the substrate slab: z = substrate_top + D/2 + r_max (r_max = largest
  // particle radius), so no substrate particle lies in a pore (eq. 1); no pores below it.
  // With a given origin the lattice fills the whole box.
  bool auto_origin = true;
  Vec3 origin{0.0, 0.0, 0.0};
};

// Repeat lengths of the FCC pore lattice along x, y, z [m]: [111] along z: (a, a sqrt 3,
// a sqrt 6) with a the nearest-neighbour distance; [100] along z: a sqrt 2 on each axis. A
// periodic box should be a whole number of these along its periodic axes (else the lattice
// has a seam there; the builder reports it).
Vec3 fcc_pore_period(const FccPores& fcc);

// A pore set: centres and radii [m].
struct PoreSet {
  std::vector<Vec3> centre;
  std::vector<double> radius;
  std::size_t size() const { return centre.size(); }
};

// The pores of `fcc` whose spheres reach into `box` (along periodic axes each pore once, wrapped
// into the box; along open axes every pore whose sphere intersects [lo, hi]).
// `pore_floor` is the z the lowest pore layer touches with the automatic origin
// (substrate_top + r_max in build_opal).
PoreSet fcc_pores(const Box& box, const FccPores& fcc, double pore_floor);

// Random pores (§4): `count` pores of `diameter` placed by the force-biased algorithm
// (generate/fba.hpp) in `region`, so that they do not overlap beyond the FBA tolerance.
//  - periodic = false: the region's periodic axes as given, walls on the others (every pore
//    wholly inside the region, typically the particle box above the substrate).
//  - periodic = true: the pore packing is periodic along every axis of the region (a pore may
//    cut the sample's faces, as the paper's pores reach its fixed layer, §2.1); a pore that
//    crosses a face along an axis where `region` itself is open is returned together with its
//    image at the opposite face, so the region loses exactly the pore volume fraction
//    count x pi D^3/6 / V(region). Walls lower the density a pore packing can reach near them,
//    so only this mode reaches the paper's porosities up to 0.63 (docs/opal-build.md).
// The pore volume fraction must be below 0.7 (the FBA's lowest porosity, 0.30). Periodic pores
// are packed with a ten times slower contraction (FbaParams::shrink_rate 0.001): the default 0.01
// jams 77 pores at fraction 0.63 in a periodic box (3 seeds of 3 stop at max_iterations with
// overlaps 1.3e-3-5.5e-3), 0.001 reaches it in 580-1,050 iterations (3 of 3). Walled pores keep
// the default (the packings of the first version, bit for bit).
// spacing_ratio (as FccPores::spacing_ratio): the pores are packed as spheres of diameter
// spacing_ratio x D, so their centres are at least that far apart, and the volume fraction
// above is that of the packed spheres; 1 = the pores themselves. docs/opal.md keeps the paper's
// relative interpore opening at a coarser resolution this way (D/d = 9.2: D = 138 nm cut
// spheres packed at 150 nm, the FCC opal's 138 nm pores at 150 nm spacing).
struct RandomPores {
  double diameter = 0.0;  // [m], > 0
  long count = 0;         // > 0
  bool periodic = false;
  double spacing_ratio = 1.0;  // in [0.5, 2]
  double fba_tolerance = 1e-3;
  long fba_max_iterations = 200000;
};
PoreSet random_pores(const Box& region, const RandomPores& options, Random& rng);
// Volume of one pore as random_pores() packs it: a sphere of spacing_ratio x diameter, so that
// count x this / region volume is the packed fraction it must stay below 0.7 for.
double packed_pore_volume(const RandomPores& options);

// The particle box above the substrate slab of `substrate_layers` mean diameters and one
// largest particle radius (so no substrate particle lies in a pore): the region for
// random_pores() in build_opal's geometry.
Box random_pore_region(const Packing& particles, double substrate_layers);

struct OpalOptions {
  // Pore set: either an FCC lattice (fcc.diameter > 0) or the explicit `pores` (random pores
  // from random_pores(), or any list); exactly one of the two.
  FccPores fcc;
  PoreSet pores;

  double coating_thickness = 0.0;  // L_coat [m], >= 0; 0 = uncoated (every particle in a pore removed)
  // Openings filter: a coating candidate is kept when its distance to the nearest remaining
  // silica particle's surface is <= opening_distance_ratio x (L_coat + R_p); 1 = the paper's rule.
  double opening_distance_ratio = 1.0;
  double substrate_layers = 2.0;    // substrate slab thickness in mean particle diameters, >= 0
  double bond_cutoff_ratio = 1.75;  // bond when d < ratio (R_i + R_j); in [1, 2)
  // Bond radius = ratio x the smaller particle radius. Not stored per bond: recorded here and
  // in the report, and applied by the bond law at test time (dem::ElasticBond::Params).
  double bond_radius_ratio = 1.0;
  // Continuum densities of the components for the reported sample density (§4: silica matrix
  // 1297 kg/m^3 [57], titania 3660 kg/m^3 [11]).
  double silica_density = 1297.0;
  double titania_density = 3660.0;
  int threads = 1;

  void validate() const;  // InputError naming key, value and allowed range
};

// Figures of the built model. "Sample" = the part of the box above the substrate slab.
struct OpalSummary {
  long input_particles = 0;
  long particles = 0;         // in the model (structural + coating + substrate)
  long structural = 0;        // silica
  long coating = 0;           // titania
  long substrate = 0;         // fixed
  long removed = 0;           // cut out by the pores
  long coating_openings = 0;  // candidates dropped to keep interpore openings free
  long pores = 0;
  long bonds = 0;
  std::array<long, 3> bonds_by_material{0, 0, 0};  // silica, titania, substrate
  long periodic_bonds = 0;                         // bonds to a periodic image (image != 0)
  double mean_coordination = 0;                    // 2 bonds / particles
  // Macro porosity of the sample: 1 - V(particles kept) / V(particles before cutting), both over
  // the particles above the substrate (the pore fraction, 0.74 for touching FCC pores).
  double porosity = 0;
  // Total porosity of the box: 1 - sum of particle volumes / box volume (includes the packing's
  // own inter-particle porosity).
  double particle_porosity = 0;
  // Sample density [kg/m^3]: sum over components of (component particle volume / particle
  // volume before cutting) x continuum density, over the sample (§4's estimate).
  double density = 0;
  double pore_diameter = 0;           // mean [m]
  double mean_particle_diameter = 0;  // [m]
  double substrate_top = 0;           // z of the substrate slab's top [m]
  double bond_radius_ratio = 1;
  bool lattice_commensurate = true;  // FCC pores fit the periodic box (no seam)
  double seconds = 0;
};

// Builds the model (steps 1–5). The result has the input's box; types structural / coating /
// substrate (core/packing.hpp); fixed = 1 for substrate; bonds with opal_bond_material; no
// velocities. `progress` (optional) receives a phase name and fraction done.
Packing build_opal(const Packing& particles, const OpalOptions& options, OpalSummary* summary = nullptr,
                   const std::function<void(const std::string&, double)>& progress = {});

// The pore set build_opal uses for these options (FCC pores generated, or options.pores).
PoreSet opal_pores(const Packing& particles, const OpalOptions& options);

}  // namespace packlab::generate
