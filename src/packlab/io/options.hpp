// The option sets of the commands, declared once (io/config.hpp): each binds the fields of a
// parameter struct to their keys, units, ranges and documentation. The command line (flags and
// config file), the Python module (keywords) and the generated reference read these, so a
// command and its Python function take the same options under the same names.
// Defined in options.cpp (generators, engine, bonds), mechanics_options.cpp (shear and
// compression tests) and analysis_options.cpp (analyses).
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>

#include "packlab/analyze/pore_size.hpp"
#include "packlab/analyze/rdf.hpp"
#include "packlab/core/box.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/dem/material.hpp"
#include "packlab/dem/relax.hpp"
#include "packlab/generate/brownian_dynamics.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/generate/lattice.hpp"
#include "packlab/generate/ls.hpp"
#include "packlab/generate/opal.hpp"
#include "packlab/generate/random.hpp"
#include "packlab/generate/scrm.hpp"
#include "packlab/generate/shake.hpp"
#include "packlab/generate/vem.hpp"
#include "packlab/io/config.hpp"
#include "packlab/mechanics/calibration.hpp"
#include "packlab/mechanics/opal_materials.hpp"
#include "packlab/mechanics/oscillatory_shear.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"

namespace packlab::io {

// The keys of one particle material under `section` (normal_stiffness, shear_stiffness,
// density, damping, friction), as the linear contact law with local damping reads them.
void add_linear_material(ConfigSchema& schema, const std::string& section, dem::Material& material);

// `packlab generate lattice` / packlab.generate_lattice: a cubic lattice in a matching box.
struct LatticeOptions {
  std::string type = generate::lattice_type_name(generate::LatticeParams{}.type);
  std::vector<double> cells = per_axis(generate::LatticeParams{}.cells);
  generate::LatticeParams lattice;         // radius and gap
  generate::LatticeParams params() const;  // validated
  template <class T>
  static std::vector<double> per_axis(const std::array<T, 3>& a) {
    return {static_cast<double>(a[0]), static_cast<double>(a[1]), static_cast<double>(a[2])};
  }
};
ConfigSchema lattice_options(LatticeOptions& o);

// `packlab generate random` / packlab.generate_random: random spheres, overlapping or not.
struct RandomOptions {
  generate::RandomPackingParams random;  // particles, radius, volume fraction
  bool no_overlap = !generate::RandomPackingParams{}.allow_overlap;
  std::vector<double> periodic = LatticeOptions::per_axis(generate::RandomPackingParams{}.periodic);
  std::vector<double> aspect = LatticeOptions::per_axis(generate::RandomPackingParams{}.aspect);
  std::uint64_t seed = 1;
  generate::RandomPackingParams params() const;  // validated
};
ConfigSchema random_options(RandomOptions& o);

// The engine's options with one material for every particle type: packlab.Engine and the
// engine part of `packlab relax`. The material's keys are all of dem::material_parameters();
// the engine checks those its contact law reads (a law's unused properties may stay outside
// their range, e.g. youngs_modulus = 0 for the linear law).
struct EngineSettings {
  dem::EngineConfig engine;  // engine.types[0]: the material
  std::string stiffness_rule = dem::stiffness_rule_name(dem::EngineConfig{}.stiffness_rule);
  std::string time_step_rule = dem::time_step_rule_name(dem::EngineConfig{}.time_step_rule);

  dem::EngineConfig config() const;  // engine with the two rules
};
void add_engine_options(ConfigSchema& schema, EngineSettings& s);
ConfigSchema engine_options(EngineSettings& s);  // the keywords of packlab.Engine

// `packlab relax` / packlab.relax: the engine's options and the relaxation's.
struct RelaxRun : EngineSettings {
  dem::RelaxOptions relax;
  std::uint64_t seed = 1;           // accepted for uniformity; relax draws no random numbers
  double checkpoint_seconds = 120;  // command line only (with --checkpoint DIR)
};
ConfigSchema relax_options(RelaxRun& r);

// The options of the algorithms (generate/*.hpp) the front ends expose, with their ranges: the
// algorithms' validate() checks these and the parameters the front ends do not set.
void add_ls_params(ConfigSchema& schema, generate::LsParams& p);
void add_shake_params(ConfigSchema& schema, generate::ShakeParams& p);
void add_fba_params(ConfigSchema& schema, generate::FbaParams& p);
void add_bd_params(ConfigSchema& schema, generate::BdParams& p);
void add_opal_params(ConfigSchema& schema, generate::OpalOptions& o);
// output.checkpoint_seconds (--checkpoint-seconds): wall-clock seconds between two checkpoints
// of a command that can resume (command line and config file only).
void add_checkpoint_seconds(ConfigSchema& schema, double& seconds);

// `packlab generate vem` / packlab.generate_vem: the void expansion method (VemParams::validate
// checks these ranges and the rules between them).
ConfigSchema vem_options(generate::VemParams& p);

// An LS start from random points: `packlab generate ls` / packlab.generate_ls, and the LS part
// of `packlab generate scrm` / packlab.generate_scrm.
struct LsOptions {
  double phi = 0.0;  // target volume fraction; 0 = grow until jammed
  long particles = 2000;
  std::vector<double> sizes{1.0};  // relative diameters of the size classes
  std::vector<double> number_fractions, volume_fractions;
  double radius = 0.5;  // of the largest class at the target [m]
  generate::LsParams ls;
  std::uint64_t seed = 1;
  generate::SizeClasses classes() const;
};
ConfigSchema ls_options(LsOptions& o);

// `packlab generate scrm` / packlab.generate_scrm: LS growth to phi alternated with shaking.
struct ScrmOptions : LsOptions {
  ScrmOptions() { phi = 0.6; }  // SCRM grows to a target
  generate::ShakeParams shake;
  long blocks_per_cycle = 5;            // LS blocks between shakes
  long shakes_per_cycle = 1;            // global shakes after each LS segment
  long final_shakes = 10;               // global shakes at the target
  generate::ScrmParams params() const;  // validated
};
ConfigSchema scrm_options(ScrmOptions& o);

// `packlab generate fba` / packlab.generate_fba: the force-biased algorithm. Give particles (the
// box follows from diameter, porosity and aspect) or box (the count follows).
struct FbaOptions {
  long particles = 0;
  std::vector<double> box;              // LX, LY, LZ [m]
  std::vector<double> aspect{1, 1, 1};  // box edge ratios with particles
  double diameter = 1.0;                // of the largest size class [m]
  std::vector<double> sizes{1.0}, number_fractions, volume_fractions;
  std::string periodic = "xyz";
  generate::FbaParams fba;
  long history_every = 10;  // iterations between two rows of the convergence history
  std::uint64_t seed = 1;
  double checkpoint_seconds = 120;  // command line only

  // The box and the sphere count the options describe (InputError for a contradiction).
  struct Setup {
    Box box;
    long count = 0;
    generate::SizeClasses classes;
  };
  Setup setup() const;
};
ConfigSchema fba_options(FbaOptions& o);

// `packlab generate bd` / packlab.generate_bd: Brownian-dynamics coagulation with the DLVO
// potential (generate/brownian_dynamics.hpp, docs/bd.md).
struct BdOptions {
  generate::BdParams bd;
  bool msd = false;  // write msd.csv (the MSD is in the Python result always)
  std::uint64_t seed = 1;
  double checkpoint_seconds = 120;  // command line only
};
ConfigSchema bd_options(BdOptions& o);

// `packlab build opal` / packlab.build_opal: an inverse-opal model from a particle packing.
struct OpalBuildOptions {
  std::string pores = "fcc";        // fcc (lattice) | random (force-biased pore packing)
  double pore_diameter = 0.0;       // D [m]; or pore_ratio
  double pore_ratio = 0.0;          // D / mean particle diameter
  std::string orientation = "111";  // FCC direction along z
  double pore_spacing = 1.0;        // FCC nearest-neighbour pore distance / D
  std::vector<double> pore_origin;  // a pore lattice point X, Y, Z [m]; empty: automatic
  long pore_count = 0;              // random pores: their number; or pore_fraction
  double pore_fraction = 0.0;
  // random pores: walls (every pore inside the box above the substrate) | periodic (the pore
  // packing periodic along z too, over the whole box: pores cut the top and bottom faces)
  std::string pore_boundary = "walls";
  generate::OpalOptions opal;
  std::uint64_t seed = 1;

  // The builder's options for `packing` with its pore set (the FCC lattice, or random pores
  // drawn with `seed`); `pores_report`, if given, receives the report's `pores` block.
  generate::OpalOptions resolve(const Packing& packing, nlohmann::json* pores_report = nullptr) const;
};
ConfigSchema opal_build_options(OpalBuildOptions& o);

// `packlab shake` / packlab.shake: Monte-Carlo shaking of a packing.
struct ShakeOptions {
  long sweeps = 10;  // global shakes M
  generate::ShakeParams shake;
  std::uint64_t seed = 1;
  double checkpoint_seconds = 120;  // command line only
};
ConfigSchema shake_options(ShakeOptions& o);

// `packlab bond` / packlab.bond: bonds between close pairs (generate/bonding.hpp).
struct BondOptions {
  std::string model = "contact";  // contact | elastic
  double eps = 0.01;
  double cutoff_ratio = 1.75;
  int threads = 1;
};
ConfigSchema bond_options(BondOptions& o);

// The options of the oscillatory shear test (mechanics/oscillatory_shear.hpp), with their
// ranges: mechanics::validate checks these and the rules between them.
void add_oscillatory_shear_options(ConfigSchema& schema, mechanics::OscillatoryShearOptions& o);

// `packlab test shear` / packlab.shear_test.
struct ShearTestRun {
  mechanics::OscillatoryShearOptions test;
  bool plots = true;
  double checkpoint_seconds = 120;  // command line only
};
ConfigSchema shear_test_options(ShearTestRun& r);

// `packlab calibrate shear` / packlab.calibrate_shear: the test's options and the target.
struct ShearCalibrationRun {
  mechanics::OscillatoryShearOptions test;
  double target_storage_modulus = 0.0;  // [Pa]
  double tolerance = 0.005;             // relative
  long max_iterations = 10;
  double checkpoint_seconds = 120;  // command line only
};
ConfigSchema shear_calibration_options(ShearCalibrationRun& r);

// The set-up options of a uniaxial compression run (mechanics/uniaxial_compression.hpp), with
// their ranges: UniaxialCompressionOptions::validate checks these and the rules between them.
void add_uniaxial_compression_options(ConfigSchema& schema, mechanics::UniaxialCompressionOptions& o);

// `packlab test compress` / packlab.compression_test: the inverse-opal materials
// (mechanics/opal_materials.hpp), the rate rule and the set-up.
ConfigSchema compression_test_options(mechanics::UniaxialCompressionSetup& s);

// `packlab calibrate compress` / packlab.calibrate_compress: a compression run's options, the
// targets and the Newton iteration (mechanics/compression_calibration.hpp).
struct CompressionCalibrationRun {
  mechanics::UniaxialCompressionSetup setup;
  double target_youngs_modulus = 0.0;  // [Pa]
  double target_strength = 0.0;        // [Pa]
  bool bulk_factor = false;
  mechanics::CalibrationOptions calibration;
  bool full_jacobian = false;
};
ConfigSchema compression_calibration_options(CompressionCalibrationRun& r);

// The analyses (analyze/*.hpp): each set is the keywords of its Python class and a part of
// `packlab analyze`, whose option set is their union.
struct CoordinationSettings {  // packlab.Coordination
  double contact_eps = 0.01;
  int rattler_threshold = 4;
  std::string rattler_rule = "iterative";
};
void add_coordination_options(ConfigSchema& schema, CoordinationSettings& s);
ConfigSchema coordination_options(CoordinationSettings& s);

struct PoreSizeSettings {  // packlab.PoreSize
  long points = 0;
  double band = 0.005;
  double confidence = 0.95;
  std::string pore_definition = "pore_space";
  double wall_margin = -1.0;
  int threads = 0;
  analyze::PoreSizeParams params() const;
};
void add_pore_size_options(ConfigSchema& schema, PoreSizeSettings& s);
ConfigSchema pore_size_options(PoreSizeSettings& s);

struct DohFitSettings {           // packlab.PoreSize.fit_doh
  double r0 = 0.0;                // [m]; 0 = mean particle radius
  std::vector<double> fit_range;  // XMIN, XMAX of r/r0; empty = 0 to where P falls to fit_p_min
  double fit_p_min = 1e-3;
  int fit_grid = 100;
  analyze::DohFitOptions options() const;  // InputError for a bad fit_range
};
void add_doh_fit_options(ConfigSchema& schema, DohFitSettings& s);
ConfigSchema doh_fit_options(DohFitSettings& s);

struct FabricSettings {  // packlab.Fabric (with contact_eps and rattler_threshold)
  int fabric_bins = 18;
  bool fabric_without_rattlers = false;
};
void add_fabric_options(ConfigSchema& schema, FabricSettings& s);
ConfigSchema fabric_options(CoordinationSettings& c, FabricSettings& s);

// `packlab analyze`: the union, plus which analyses to run and the box of files without one.
struct AnalyzeRun {
  std::string what = "all";
  CoordinationSettings coordination;
  PoreSizeSettings pores;
  DohFitSettings fit;
  FabricSettings fabric;
  std::vector<double> box, origin, periodic;
  std::uint64_t seed = 1;
};
ConfigSchema analyze_options(AnalyzeRun& r);

// `packlab analyze rdf` / packlab.Rdf.
struct RdfSettings {
  analyze::RdfParams params;
  std::string edge = "auto";
  bool partial = false;
  analyze::RdfParams validated() const;  // params with the edge correction
};
ConfigSchema rdf_options(RdfSettings& s);

}  // namespace packlab::io
