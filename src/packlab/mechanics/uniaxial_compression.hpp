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
// Evaluation: Young's modulus by the "max_tangent" fit and the strength (peak stress) of
// analyze/stress_strain.hpp (modulus_lower, modulus_window are its fractions). The materials
// of the inverse-opal models and the rate rule of the front ends: mechanics/opal_materials.hpp.
//
// Files: uniaxial_compression_setup.cpp (options, the specimen: substrate, plate, bonds,
// cross-section), uniaxial_compression.cpp (the loading protocol and the result's columns).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <istream>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "packlab/analyze/stress_strain.hpp"
#include "packlab/core/columns.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/dem/engine.hpp"

namespace packlab::mechanics {

struct UniaxialCompressionPoint {
  long step = 0;
  double time = 0.0;             // [s]
  double displacement = 0.0;     // plate [m]
  double strain = 0.0;           // displacement / H0 [-]
  double force = 0.0;            // plate reaction, compressive positive [N]
  double stress = 0.0;           // force / A [Pa]
  double kinetic_energy = 0.0;   // [J]
  double strain_energy = 0.0;    // [J]
  std::size_t broken_bonds = 0;  // since the start of the test
};

// State at a requested strain: bond strains (input bond order of the model as run; NaN for
// failed bonds) and per-particle Cauchy stress (eq. 21, packing order, row-major 3x3).
// A snapshot is requested either at a strain (requested_strain; requested_stress NaN) or at an
// applied stress (requested_stress; requested_strain NaN): taken where the run first reaches it.
struct UniaxialCompressionSnapshot {
  double requested_strain = 0.0;
  double requested_stress = std::numeric_limits<double>::quiet_NaN();  // [Pa]
  double strain = 0.0;
  double stress = 0.0;
  std::vector<double> bond_strain;
  std::vector<std::array<double, 9>> particle_stress;
  bool by_stress() const { return !std::isnan(requested_stress); }
};

struct UniaxialCompressionOptions {
  std::vector<dem::Material> types;                      // per particle type (one entry: all)
  std::vector<dem::ElasticBond::Params> bond_materials;  // per bond material (one entry: all)
  double strain_rate = 1e7;                              // [1/s]
  // Dynamic solver, adaptive rate (issue #14): the plate moves elastic_speedup times faster, with
  // the curve points at the same strain spacing, until the first bond breaks; the run then goes
  // back to the curve point before that break and goes on at strain_rate from there, so that no
  // bond breaks at the fast rate. 1 = strain_rate throughout. What it changes: docs/opal.md.
  double elastic_speedup = 1.0;
  double max_strain = 0.05;  // [-]
  // Stop once past the peak when the stress has fallen below stop_drop x peak (0: run to
  // max_strain); the static solver also stops once no later point can come back above it.
  double stop_drop = 0.6;
  std::string sides = "periodic";  // "periodic" | "open"
  double substrate_layers = 2.0;   // used when the model has no fixed particle
  std::string plate = "glued";     // "glued" | "contact" (see the header comment)
  double plate_layers = 2.0;       // glued plate: top layers moving with it (mean diameters)
  double time_step = 0.0;          // 0 = automatic (safety x min sqrt(m/k) over bonds and contacts)
  double time_step_safety = 0.2;
  long samples = 400;                    // curve points over max_strain (about)
  std::vector<double> snapshot_strains;  // strains for bond strain / particle stress snapshots
  // Applied stresses [Pa] for the same snapshots (Table 2 is at 31.3 MPa), each taken where the
  // stress first reaches it: dynamic, at the first curve point at or above it; static, on the
  // first linear branch whose break load reaches it, at the strain where that branch carries it
  // exactly. A stress the run never reaches gives no snapshot.
  std::vector<double> snapshot_stresses;
  double modulus_lower = 0.05;  // see the header comment
  double modulus_window = 0.25;
  int threads = 1;
  bool adapt_threads = true;  // dynamic solver: dem::EngineConfig::adapt_threads
  // "dynamic": the explicit DEM run above; "static": the quasi-static solver with sequential
  // linear analysis (mechanics/static_loading.hpp, docs/static-solver.md).
  std::string solver = "dynamic";
  std::string solver_backend = "auto";  // static: "auto", "cholmod", "eigen" or "petsc"
  std::string petsc_options;            // static, petsc backend: PETSc options (docs/static-solver.md)
  long max_breaks = 0;                  // static: stop after this many bond breaks (0 = no limit)
  // static: re-solves after bond removals checked against the matrix every check_interval-th
  // (1 = each); a failed check rolls the analysis back to the last checked break (static_solver.hpp).
  int check_interval = 16;
  double check_tolerance = 1e-10;  // static: relative residual and energy-norm error of a check (API only)
  // static: at the first verified solve once another checkpoint_breaks bonds have broken, the
  // state is a checkpoint (written when checkpoint_seconds have passed) and the next solve
  // factorizes anew: a resumed run starts with that fresh factorization, as the uninterrupted
  // run does, and gives its bits.
  long checkpoint_breaks = 2000;
  // Called at each curve point (progress); may be empty.
  std::function<void(const UniaxialCompressionPoint&)> on_point;
  // Resumable runs (`packlab test compress --resume`, cli/checkpoint.hpp): `checkpoint` is
  // called with a writer of the whole state (dynamic: the engine's, the curve, the peak, the
  // snapshots) after each curve point and once more at the end (`end` true); static: the broken
  // bonds in order, the envelope, the peak, the snapshots and the solver's counts at each
  // checkpoint_breaks point (above). A run given `resume`, a stream positioned at such a state,
  // goes on from it exactly as the saved run would have.
  std::function<void(const std::function<void(std::ostream&)>& state, bool end)> checkpoint;
  std::istream* resume = nullptr;
  void validate() const;  // InputError naming key, value and allowed range
};

struct UniaxialCompressionResult {
  std::vector<UniaxialCompressionPoint> curve;
  analyze::ModulusFit modulus;
  double youngs_modulus = 0.0;  // [Pa]
  double strength = 0.0;        // peak stress [Pa]
  double strain_at_peak = 0.0;
  double height = 0.0;       // H0 [m]
  double area = 0.0;         // A [m^2]
  double plate_speed = 0.0;  // [m/s] at strain_rate
  // Dynamic solver with elastic_speedup > 1: the speed-up run (interval / fast interval of the
  // curve points: elastic_speedup rounded so that the points keep their spacing; 1 = none), the
  // strain where the plate slowed to strain_rate (one fast step after the last curve point before
  // the first break; NaN when no bond broke) and the fast steps discarded at that break.
  double effective_speedup = 1.0;
  double rate_switch_strain = std::numeric_limits<double>::quiet_NaN();
  long rolled_back_steps = 0;
  double time_step = 0.0;  // [s]
  long steps = 0;
  double max_kinetic_ratio = 0.0;  // max kinetic / strain energy over points with stress > 0.2 peak
  std::size_t particles = 0, fixed_particles = 0, glued_particles = 0;
  std::size_t bonds = 0;          // bonds in the run (intact at the start)
  std::size_t dropped_bonds = 0;  // left out: across opened boundaries, or between two fixed particles
  std::size_t broken_bonds = 0;
  std::string stop_reason;
  std::vector<UniaxialCompressionSnapshot> snapshots;
  std::vector<dem::BondBreak> breaks;                                  // bond index = index into `model.bonds`
  std::vector<double> break_strain;                                    // the strain at each break [-]
  std::string solver = "dynamic";                                      // which solver ran the test
  double poisson_ratio = std::numeric_limits<double>::quiet_NaN();     // static, open sides: -eps_lateral / eps_axial
  std::size_t solves = 0;                                              // static: linear solves
  std::size_t factorizations = 0;                                      // static: matrix factorizations
  std::size_t solver_bytes = 0;                                        // static: matrix and factor memory [B]
  std::size_t unknowns = 0, matrix_nonzeros = 0, factor_nonzeros = 0;  // static
  long pcg_iterations = 0;                                             // static
  long downdates = 0;                                                  // static: bonds taken out of the factor
  long checks = 0;                                                     // static: re-solves checked against the matrix
  long rollbacks = 0;  // static: checks that found the factor drifted (the analysis went back)
  double factor_seconds = 0.0, solve_seconds = 0.0, downdate_seconds = 0.0;  // static [s]
  double check_seconds = 0.0;  // static: of solve_seconds, the checks of re-solves after downdates [s]
  Packing model;               // the model as run (final positions, bond states)
  double seconds = 0.0;
};

// The specimen as the test runs it: the model with the opened axes, the substrate and (glued
// plate) the top layers fixed, the bonds that carry load; H0, A and the counts go into `result`.
struct UniaxialCompressionSpecimen {
  Packing model;
  std::vector<std::uint8_t> grip;  // 1 = glued to the plate
  double top = 0.0;                // highest particle top [m] (the contact plate starts there)
};
UniaxialCompressionSpecimen prepare_uniaxial_compression(const Packing& bonded_model,
                                                         const UniaxialCompressionOptions& options,
                                                         UniaxialCompressionResult& result);

// The engine a compression runs (and the static solver linearizes): the Hertz–Mindlin contact
// law with the options' particle types, bond materials, time step and threads.
dem::EngineConfig compression_engine_config(const UniaxialCompressionOptions& options);

// The curve as columns (curve.csv, Python's result.curve): step, time, displacement, strain,
// force, stress, kinetic_energy, strain_energy, broken_bonds.
Columns curve_columns(const std::vector<UniaxialCompressionPoint>& curve);

// InputError on a model without bonds, periodic z that cannot be opened, bad options.
UniaxialCompressionResult run_uniaxial_compression(const Packing& bonded_model,
                                                   const UniaxialCompressionOptions& options);

}  // namespace packlab::mechanics
