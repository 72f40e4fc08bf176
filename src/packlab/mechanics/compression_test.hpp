// Uniaxial compression of a bonded-particle model (bpm-inverse-opals §2.2, §3): a plate above
// the sample moves down at a constant strain rate against a fixed substrate; the plate's
// reaction force gives the force-displacement and stress-strain curves, the Young's modulus
// (linear part) and the compressive strength (peak), bond strain distributions at chosen
// strains (Fig. 7), per-particle Cauchy stresses (eq. 21, Table 2) and the broken bonds over
// time with their positions.
//
// Set-up, every choice a named option:
//  - Loading axis z. The box must be open along z; a model periodic along z is opened and its
//    bonds across the z boundary are dropped (reported).
//  - Sides x, y: "periodic" (the model's periodic axes stay periodic: a laterally confined
//    RVE, as the paper's PBC runs) or "open" (periodic axes are opened and bonds across them
//    dropped: a free-standing pillar, the paper's open boundaries).
//  - Substrate: the model's fixed particles; when it has none, the particles whose centre lies
//    below z_min + (substrate_layers - 1/2) d_mean (z_min the lowest centre, d_mean the mean
//    diameter: exactly the bottom `substrate_layers` levels of a lattice) are fixed. Bonds
//    between two fixed particles carry no load and are left out of the run.
//  - Plate, two kinds:
//    "contact" (the paper's): a Hertz-Mindlin wall (the touching particle's material) starting
//      at the top of the highest particle; H0 = plate start - lowest particle bottom. The top
//      surface of a random packing is rough by about a particle radius, so the curve starts with
//      a toe of about r / H0 of strain while the plate finds its contacts (0.5 % in the paper
//      at H0 = 133 d; several % at the reduced heights of 20-40 d used here).
//    "glued": the particles whose centre lies above z_max - (plate_layers - 1/2) d_mean are
//      bonded to the plate (they move with it, like the fixed substrate); H0 = the gauge length
//      between the lowest glued centre and the highest substrate centre, the plate force = the
//      force the sample exerts on the glued particles. No toe: the sample's own response.
//    The plate moves down at v = strain_rate x H0. Strain = plate displacement / H0, stress =
//    plate force / A with A = the periodic cross-section Lx Ly, or the x-y extent of the spheres
//    when the sides are open. Both compressive positive.
//  - Quasi-static: the run is dynamic; the rate must be low enough that the result does not
//    depend on it (DESIGN.md numerical notes). Local damping (Material::damping) removes the
//    elastic waves; the report carries the largest kinetic / strain energy ratio seen.
//
// Young's modulus (the "linear slope of the stress-strain diagram", §3.1.2), method
// "max_tangent": least-squares slopes over sliding windows that each span `modulus_window` x
// the peak stress, on the points before the peak with stress >= modulus_lower x peak; E is the
// largest such slope (the plateau of the tangent modulus, Fig. 10's region 2, past the initial
// plate-contact toe and before damage softens the curve). Strength: the peak stress.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "packlab/core/packing.hpp"
#include "packlab/dem/engine.hpp"

namespace packlab::mechanics {

// The paper's materials (bpm-inverse-opals Table 1, §3.2, §4): bond and particle Young's
// modulus, Poisson ratio, strength; densities of the simulations (1297, 3660 kg/m^3).
struct OpalMaterials {
  double silica_youngs_modulus = 6.53e9;   // E_b [Pa]
  double silica_poisson_ratio = 0.17;      // [-]
  double silica_strength = 94.3e6;         // sigma_max = tau_max [Pa]
  double silica_density = 1297.0;          // [kg/m^3]
  double titania_youngs_modulus = 17.89e9; // 20 nm coating (Table 1) [Pa]
  double titania_poisson_ratio = 0.28;
  double titania_strength = 834e6;
  double titania_density = 3660.0;
  // Contacts of unbonded pairs and with the plate (the paper gives no values; documented
  // defaults): restitution, sliding and rolling friction; local damping for quasi-static runs.
  double restitution = 0.5;
  double friction = 0.3;
  double rolling_friction = 0.01;
  double damping = 0.7;
  double bond_radius_ratio = 1.0;          // R_b / min(r_i, r_j)
  double relaxation_time = 1e-9;           // [s] (1 % stiffness per 1e-11 s)
  bool compressive_breakage = false;       // eq. 16 for compressed bonds too (dem/bond/elastic_bond.hpp)
};

// Per particle type (structural, void, pore, coating, substrate: core/packing.hpp) Hertz-Mindlin
// parameters, and per bond material (generate/opal.hpp: silica, titania, substrate) elastic
// bond parameters. Substrate particles and substrate-substrate bonds take silica's values.
std::vector<dem::Material> opal_particle_types(const OpalMaterials& m);
std::vector<dem::ElasticBond::Params> opal_bond_materials(const OpalMaterials& m);

struct CompressionPoint {
  long step = 0;
  double time = 0.0;            // [s]
  double displacement = 0.0;    // plate [m]
  double strain = 0.0;          // displacement / H0 [-]
  double force = 0.0;           // plate reaction, compressive positive [N]
  double stress = 0.0;          // force / A [Pa]
  double kinetic_energy = 0.0;  // [J]
  double strain_energy = 0.0;   // [J]
  std::size_t broken_bonds = 0; // since the start of the test
};

// State at a requested strain: bond strains (input bond order of the model as run; NaN for
// failed bonds) and per-particle Cauchy stress (eq. 21, packing order, row-major 3x3).
struct CompressionSnapshot {
  double requested_strain = 0.0;
  double strain = 0.0;
  double stress = 0.0;
  std::vector<double> bond_strain;
  std::vector<std::array<double, 9>> particle_stress;
};

// Mean and standard deviation of the per-particle stress of one particle type (free particles).
struct TypeStress {
  int type = 0;
  std::size_t particles = 0;
  std::array<double, 3> mean{};  // sigma_xx, sigma_yy, sigma_zz [Pa], tension positive
  std::array<double, 3> sd{};
};

struct ModulusFit {
  double youngs_modulus = 0.0;  // slope [Pa]
  double intercept = 0.0;       // [Pa]
  double strain_begin = 0.0, strain_end = 0.0;  // window of the fit
  double r2 = 0.0;
  int points = 0;
  bool found = false;
};

struct CompressionOptions {
  std::vector<dem::Material> types;                   // per particle type (one entry: all)
  std::vector<dem::ElasticBond::Params> bond_materials; // per bond material (one entry: all)
  double strain_rate = 1e7;       // [1/s]
  double max_strain = 0.05;       // [-]
  // Stop once past the peak when the stress has fallen below stop_drop x peak (0: run to
  // max_strain).
  double stop_drop = 0.6;
  std::string sides = "periodic";  // "periodic" | "open"
  double substrate_layers = 2.0;   // used when the model has no fixed particle
  std::string plate = "glued";     // "glued" | "contact" (see the header comment)
  double plate_layers = 2.0;       // glued plate: top layers moving with it (mean diameters)
  double time_step = 0.0;          // 0 = automatic (safety x min sqrt(m/k) over bonds and contacts)
  double time_step_safety = 0.2;
  long samples = 400;              // curve points over max_strain (about)
  std::vector<double> snapshot_strains;  // strains for bond strain / particle stress snapshots
  double modulus_lower = 0.05;     // see the header comment
  double modulus_window = 0.25;
  int threads = 1;
  // Called at each curve point (progress); may be empty.
  std::function<void(const CompressionPoint&)> on_point;
  void validate() const;  // InputError naming key, value and allowed range
};

struct CompressionResult {
  std::vector<CompressionPoint> curve;
  ModulusFit modulus;
  double youngs_modulus = 0.0;  // [Pa]
  double strength = 0.0;        // peak stress [Pa]
  double strain_at_peak = 0.0;
  double height = 0.0;          // H0 [m]
  double area = 0.0;            // A [m^2]
  double plate_speed = 0.0;     // [m/s]
  double time_step = 0.0;       // [s]
  long steps = 0;
  double max_kinetic_ratio = 0.0;  // max kinetic / strain energy over points with stress > 0.2 peak
  std::size_t particles = 0, fixed_particles = 0, glued_particles = 0;
  std::size_t bonds = 0;            // bonds in the run (intact at the start)
  std::size_t dropped_bonds = 0;    // left out: across opened boundaries, or between two fixed particles
  std::size_t broken_bonds = 0;
  std::string stop_reason;
  std::vector<CompressionSnapshot> snapshots;
  std::vector<dem::BondBreak> breaks;  // bond index = index into `model.bonds`
  Packing model;                       // the model as run (final positions, bond states)
  double seconds = 0.0;
};

// Everything a compression run of an opal-type model needs, as the command line sets it:
// materials, test options and the rate rule. finish(model) fills options.types,
// options.bond_materials, options.snapshot_strains and options.strain_rate.
struct CompressionSetup {
  OpalMaterials materials;
  CompressionOptions options;
  std::vector<double> snapshot_strains;
  double strain_rate = 0.0;     // [1/s]; 0 = automatic
  // Automatic rate: this strain per time an elastic wave needs to cross the sample,
  // H0 / c with c = sqrt(E_b / rho) of silica (DESIGN.md: quasi-static, shown rate-independent).
  double quasi_static = 1e-4;
  void finish(const Packing& model);
};

// InputError on a model without bonds, periodic z that cannot be opened, bad options.
CompressionResult run_compression(const Packing& bonded_model, const CompressionOptions& options);

// The "max_tangent" modulus of a stress-strain curve (see the header comment); points after
// the peak are ignored.
ModulusFit fit_youngs_modulus(const std::vector<double>& strain, const std::vector<double>& stress,
                              double lower_fraction = 0.05, double window_fraction = 0.25);

// Per-type mean and standard deviation of sigma_xx, sigma_yy, sigma_zz over free particles.
std::vector<TypeStress> stress_by_type(const Packing& model, const std::vector<std::array<double, 9>>& stress);

// Histogram of the finite values: `bins` equal bins over [lo, hi]; returns counts.
std::vector<std::size_t> histogram(const std::vector<double>& values, double lo, double hi, int bins);

}  // namespace packlab::mechanics

#include <filesystem>
#include <nlohmann/json.hpp>

namespace packlab::mechanics {

// The results as JSON (SI units; keys youngs_modulus, strength, broken_bonds, ...).
nlohmann::json compression_report(const CompressionResult& result, const CompressionOptions& options);

// Writes into `dir`: curve.csv (+ stress_strain.png, force_displacement.png, broken_bonds.png),
// bond_strain.csv (+ bond_strain.png, Fig. 7) and particle_stress.csv when snapshots were taken,
// broken_bonds.csv and broken_bonds.vtu (failure positions with time and strain), model.vtu
// (final state, bond states) when `write_model`. Plots only when `plots`.
void write_compression_outputs(const CompressionResult& result, const CompressionOptions& options,
                               const std::filesystem::path& dir, bool plots, bool write_model);

}  // namespace packlab::mechanics
