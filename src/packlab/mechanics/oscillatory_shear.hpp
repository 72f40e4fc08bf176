// Oscillatory shear test of a bonded packing (doh-elastic-properties §2.4, Fig. 3-4):
//
//  - the structure is periodic along the shear direction x' and the third axis y'; along the
//    plate normal z' it lies between two plates made of `plate_layers` particle layers (a slab
//    of plate_layers * 2 <r> taken from the periodic repetition of the structure, i.e. its
//    periodic images just below and just above the box); bonds that crossed the z' boundary of
//    the periodic structure now bond the structure to the plates;
//  - the lower plate is fixed, the upper plate is displaced along x' at constant volume:
//    u(t) = A_c sin(2 pi t / T) in cycle c = 1..cycles with A_c = c / cycles * amplitude * H
//    (linearly increasing amplitude up to amplitude * H, H the box edge along z');
//  - the shear stress sigma_x'z' (symmetric part) is measured in `regions` horizontal
//    measurement slabs at several heights (sigma = 1/V_region sum_{p in region} 1/2 sum_c l F,
//    the particle-stress sum of dem::particle_stress) and, as a check, from the force on the
//    upper plate;
//  - per cycle |G*| = peak-to-peak stress / peak-to-peak strain (the paper's "peak shear stress
//    divided by the actual peak strain", insensitive to an offset), the phase angle delta from
//    a least-squares fit sigma = a sin(wt) + b cos(wt) + c (delta = atan2(b, a)), and
//    G' = |G*| cos(delta);
//  - six orientations: plate normal along x, y, z, shear along each of the two other axes
//    (the packing's coordinates are permuted so that the normal is z' and the shear x').
//
// The paper's 1 Hz cannot be run with a ~1e-10 s step (1e10 steps per cycle): the test runs
// quasi-statically with a cycle length in steps (`steps_per_cycle`); docs/shear.md shows that
// G' does not change when the cycle is made slower and the phase angle stays near zero.
//
// Files: oscillatory_shear_setup.cpp (orientations, options, relaxation, plates),
// oscillatory_shear.cpp (the loading), oscillatory_shear_evaluation.cpp (the per-cycle fit);
// the calibration of k_n: shear_calibration.hpp.
//
// Before the test the periodic structure is relaxed by the procedure of §2.2
// (dem::relax_zeroing_velocities) unless `relax` is false; the shear histories it builds are not
// carried into the test set-up, which is therefore settled by the same procedure (plates fixed)
// before the first cycle unless `settle` is false.
#pragma once

#include <functional>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "packlab/core/columns.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/dem/relax.hpp"

namespace packlab::mechanics {

// Plate normal and shear direction as axis indices (0 = x, 1 = y, 2 = z), normal != direction.
struct ShearOrientation {
  int normal = 2;
  int direction = 0;
};

// "all" (the six orientations), or a comma-separated list of plate normals ("x,z": each with
// both shear directions), or of normal:direction pairs ("z:x,x:y"). InputError otherwise.
std::vector<ShearOrientation> shear_orientations(const std::string& spec);
// "normal z, shear x" as "z:x".
std::string orientation_name(const ShearOrientation& o);

struct OscillatoryShearOptions {
  // Material (Table 1). Stiffnesses are PFC particle stiffnesses under the "particle" rule (the
  // contact and the bond then act with k/2, two particle springs in series, as in PFC3D), or
  // contact stiffnesses under the "contact" rule.
  double normal_stiffness = 100.0;  // k_n [N/m]
  double shear_stiffness = 10.0;    // k_s [N/m]
  double normal_strength = 1e-4;    // F_nB [N]
  double shear_strength = 1e-6;     // F_sB [N]
  double friction = 0.0;            // mu [-] (unbonded contacts only)
  double damping = 0.9;             // local damping alpha [-]
  double density = 3690.0;          // [kg/m^3], used when the packing has none per particle
  std::string stiffness_rule = "particle";
  // Loading.
  int cycles = 10;
  double amplitude = 1e-3;  // largest plate deflection / box edge [-]
  long steps_per_cycle = 20000;
  int samples_per_cycle = 40;  // stress samples per cycle; a multiple of 4 dividing steps_per_cycle
  int plate_layers = 3;
  int regions = 3;  // measurement slabs at heights H (k+1)/(regions+1), thickness H/(regions+1)
  double time_step_safety = 0.2;
  // §2.2 relaxation of the periodic structure (relax), and the settling of the set-up with the
  // same procedure and criterion (settle).
  bool relax = true;
  bool settle = true;
  dem::ZeroVelocityRelaxOptions relax_options{};
  int threads = 1;
  bool adapt_threads = true;  // dynamic solver: dem::EngineConfig::adapt_threads
  // Which orientations to run, as shear_orientations() reads them: "all", "x,z", "z:x,x:y".
  std::string orientations = "all";
  // "dynamic": the oscillating plate above; "static": one linear solve per orientation with the
  // same set-up, the upper plate displaced by amplitude x H (mechanics/static_loading.hpp).
  std::string solver = "dynamic";
  std::string solver_backend = "auto";  // static: "auto", "cholmod", "eigen" or "petsc"
  std::string petsc_options;            // static, petsc backend: PETSc options (docs/static-solver.md)
  // Called now and then: stage ("relax", "z:x", ...), steps done and total of that stage.
  std::function<void(const std::string& stage, long done, long total)> progress;
  // Resumable tests (`packlab test shear --resume`, cli/checkpoint.hpp): `checkpoint` is called
  // after the relaxation and after each orientation with a writer of the progress
  // (save_shear_progress), and once more at the end (`end` true); a test given `resume`, a
  // stream positioned at such a state, goes on with the next orientation and gives the result
  // of an uninterrupted test (an orientation that was interrupted is run again from its start).
  // The static solver takes no checkpoints (it ignores both).
  std::function<void(const std::function<void(std::ostream&)>& state, bool end)> checkpoint;
  std::istream* resume = nullptr;
};

// Throws InputError naming the option that is out of range (the ranges of the option set
// io::shear_options declares, and the rules between options).
void validate(const OscillatoryShearOptions& options);

// The engine configuration the test uses (contact law, bond material, time step safety, threads).
dem::EngineConfig shear_engine_config(const OscillatoryShearOptions& options);

// The §2.2 relaxation of a periodic bonded packing; returns it with the new positions (velocities zero).
Packing relax_bonded(const Packing& bonded, const OscillatoryShearOptions& options,
                     dem::ZeroVelocityRelaxResult* result = nullptr);

// The packing with coordinates, box and bond images permuted so that the plate normal is z'
// and the shear direction x' (x' = old direction axis, y' = the third axis, z' = old normal).
Packing oriented_packing(const Packing& packing, const ShearOrientation& orientation);

// The test set-up built from an oriented periodic packing: structure particles first (same
// order), then the lower and the upper plate particles (fixed). `role`: 0 structure, 1 lower
// plate, 2 upper plate. `region`: measurement slab of each structure particle, -1 for none.
struct ShearSetup {
  Packing packing;
  std::vector<int> role;
  std::vector<int> region;
  double height = 0.0;            // H: the box edge along z' [m]
  double area = 0.0;              // L_x' L_y' [m^2]
  double region_thickness = 0.0;  // [m]
  std::size_t structure = 0, lower = 0, upper = 0;
};
ShearSetup build_shear_setup(const Packing& oriented, int plate_layers, int regions);

struct ShearSample {
  int cycle = 0;                      // 1-based
  long step = 0;                      // steps since the start of the loading
  double time = 0.0;                  // [s]
  double phase = 0.0;                 // 2 pi t / T within the cycle [rad]
  double strain = 0.0;                // gamma = plate deflection / H [-]
  double stress = 0.0;                // mean over the measurement regions [Pa]
  double plate_stress = 0.0;          // -F_x'(on the upper plate) / area [Pa]
  std::vector<double> region_stress;  // [Pa]
  double kinetic_energy = 0.0;        // [J]
  double strain_energy = 0.0;         // [J]
};

struct ShearCycle {
  int cycle = 0;
  double strain_amplitude = 0.0;       // half the peak-to-peak strain [-]
  double stress_amplitude = 0.0;       // half the peak-to-peak stress [Pa]
  double complex_modulus = 0.0;        // |G*| [Pa]
  double phase_angle = 0.0;            // delta [rad]
  double storage_modulus = 0.0;        // G' = |G*| cos(delta) [Pa]
  double loss_modulus = 0.0;           // G'' = |G*| sin(delta) [Pa]
  double plate_storage_modulus = 0.0;  // the same from the plate force [Pa]
};

// The shear stress sigma_x'z' of a state: per measurement region (the particle-stress sum over
// the region's particles / region volume, symmetric part, tension positive) and from the force
// on the upper plate (-F_x' / area); the largest bond tension and shear force [Pa, N].
struct ShearStress {
  std::vector<double> region_stress;
  double stress = 0.0;  // mean over the regions
  double plate_stress = 0.0;
  double max_bond_tension = 0.0, max_bond_shear_force = 0.0;
};
ShearStress shear_stress(const dem::ContactForces& forces, const ShearSetup& setup, int regions);

// Per-cycle moduli from samples of one cycle taken at phases 2 pi k / n (any offset allowed).
ShearCycle evaluate_cycle(const std::vector<ShearSample>& samples, int cycle);

// The samples as columns (stress_strain.csv, Python's samples): cycle, step, time, phase,
// strain, stress, plate_stress, region_0 .. region_{regions-1}, kinetic_energy, strain_energy.
Columns shear_sample_columns(const std::vector<ShearSample>& samples, int regions);
// The cycles as columns (cycles.csv): cycle, strain_amplitude, stress_amplitude,
// complex_modulus, phase_angle, storage_modulus, loss_modulus, plate_storage_modulus.
Columns shear_cycle_columns(const std::vector<ShearCycle>& cycles);

struct ShearRun {
  ShearOrientation orientation;
  std::vector<ShearSample> samples;
  std::vector<ShearCycle> cycles;
  double storage_modulus = 0.0;  // mean G' over the cycles [Pa]
  double complex_modulus = 0.0;  // mean |G*| [Pa]
  double phase_angle = 0.0;      // mean delta [rad]
  double plate_storage_modulus = 0.0;
  std::size_t structure_particles = 0, plate_particles = 0, bonds = 0;
  std::size_t broken_bonds = 0;         // bonds broken during the loading
  double max_bond_tension_ratio = 0.0;  // max over samples and bonds of tension / F_nB
  double max_bond_shear_ratio = 0.0;    // max of |F_s| / F_sB
  double max_bond_shear_force = 0.0;    // [N]
  double max_bond_tension = 0.0;        // [N]
  double max_kinetic_to_strain = 0.0;   // largest E_kin over largest E_strain of the samples
  dem::ZeroVelocityRelaxResult settle;
  double time_step = 0.0;
  long steps = 0;
  double seconds = 0.0;
  std::string solver = "dynamic";
  std::size_t solver_bytes = 0;  // static: matrix and factor memory [B]
};

// One orientation of an already relaxed periodic bonded packing.
ShearRun run_shear_orientation(const Packing& bonded, const ShearOrientation& orientation,
                               const OscillatoryShearOptions& options);

struct OscillatoryShearResult {
  std::vector<ShearRun> runs;
  double storage_modulus_mean = 0.0;  // [Pa]
  double storage_modulus_std = 0.0;   // sample standard deviation over orientations [Pa]
  double phase_angle_mean = 0.0;      // [rad]
  double phase_angle_max = 0.0;       // largest |delta| of any cycle [rad]
  dem::ZeroVelocityRelaxResult relax;
  bool relaxed = false;
  Packing relaxed_packing;  // the structure that was tested
  double seconds = 0.0;
  double particle_steps = 0.0;  // particles x steps over every run (relaxations included)
};

// InputError when the packing is not periodic along all three axes or has no intact bond.
OscillatoryShearResult run_oscillatory_shear(const Packing& bonded, const OscillatoryShearOptions& options);

// The relaxed structure, its relaxation and the finished orientations of a test in progress,
// exactly (oscillatory_shear_checkpoint.cpp); InputError when damaged.
void save_shear_progress(std::ostream& out, const OscillatoryShearResult& result);
void load_shear_progress(std::istream& in, OscillatoryShearResult& result);

}  // namespace packlab::mechanics
