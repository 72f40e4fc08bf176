// The materials of the inverse-opal models (bpm-inverse-opals Table 1, §3.2, §4) as DEM
// parameters, and the set-up of a compression run of such a model as the front ends make it.
#pragma once

#include <vector>

#include "packlab/core/packing.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"

namespace packlab::mechanics {

// The paper's materials (bpm-inverse-opals Table 1, §3.2, §4): bond and particle Young's
// modulus, Poisson ratio, strength; densities of the simulations (1297, 3660 kg/m^3).
struct OpalMaterials {
  double silica_youngs_modulus = 6.53e9;    // E_b [Pa]
  double silica_poisson_ratio = 0.17;       // [-]
  double silica_strength = 94.3e6;          // sigma_max = tau_max [Pa]
  double silica_density = 1297.0;           // [kg/m^3]
  double titania_youngs_modulus = 17.89e9;  // 20 nm coating (Table 1) [Pa]
  double titania_poisson_ratio = 0.28;
  double titania_strength = 834e6;
  double titania_density = 3660.0;
  // Contacts of unbonded pairs and with the plate (the paper gives no values; documented
  // defaults): restitution, sliding and rolling friction; local damping for quasi-static runs.
  double restitution = 0.5;
  double friction = 0.3;
  double rolling_friction = 0.01;
  double damping = 0.7;
  double bond_radius_ratio = 1.0;     // R_b / min(r_i, r_j)
  double relaxation_time = 1e-9;      // [s] (1 % stiffness per 1e-11 s)
  bool compressive_breakage = false;  // eq. 16 for compressed bonds too (dem/bond/elastic_bond.hpp)
};

// Per particle type (structural, void, pore, coating, substrate: core/packing.hpp) Hertz-Mindlin
// parameters, and per bond material (generate/opal.hpp: silica, titania, substrate) elastic
// bond parameters. Substrate particles and substrate-substrate bonds take silica's values.
std::vector<dem::Material> opal_particle_types(const OpalMaterials& m);
std::vector<dem::ElasticBond::Params> opal_bond_materials(const OpalMaterials& m);

// Everything a compression run of an opal-type model needs, as the command line sets it:
// materials, test options and the rate rule. finish(model) fills options.types,
// options.bond_materials, options.snapshot_strains, options.snapshot_stresses and options.strain_rate.
struct UniaxialCompressionSetup {
  OpalMaterials materials;
  UniaxialCompressionOptions options;
  std::vector<double> snapshot_strains;
  std::vector<double> snapshot_stresses;  // [Pa]
  double strain_rate = 0.0;               // [1/s]; 0 = automatic
  // Automatic rate: this strain per time an elastic wave needs to cross the sample,
  // H0 / c with c = sqrt(E_b / rho) of silica (DESIGN.md: quasi-static, shown rate-independent).
  double quasi_static = 1e-4;
  double checkpoint_seconds = 120;  // `packlab test compress` only: seconds between checkpoints
  void finish(const Packing& model);
};

}  // namespace packlab::mechanics
