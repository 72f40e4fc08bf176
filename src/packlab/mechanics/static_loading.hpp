// The mechanical tests with the quasi-static solver (static_solver.hpp) instead of explicit
// dynamics: the same specimens, boundary conditions, result types and files.
//
//  - Uniaxial compression (uniaxial_compression.hpp, solver = "static"): substrate fixed, the
//    glued plate layers displaced down; Young's modulus E = (F / A) / (displacement / H0) of the
//    intact network from one solve; Poisson's ratio from the lateral displacements of the free
//    particles (open sides; NaN when the sides are periodic, which confine them). Strength by
//    sequential linear analysis: the linear solution at unit strain gives every intact bond's
//    failure_ratio (its criteria, eq. 16-17 for the elastic bond); the bond with the largest
//    ratio breaks at strain 1 / ratio, where the envelope records (strain, stress); it is
//    removed and the network solved again, until the stress at a break falls below stop_drop x
//    the peak after the peak, max_strain times the stress per unit strain does (no later point
//    can come back above it), the strain passes max_strain, or max_breaks bonds have broken.
//    Snapshots (bond strains, particle stresses) at the requested strains from the network as
//    it stands then. Contacts between unbonded particles enter with their stiffness at the
//    start; they neither open nor slide, and a broken bond does not turn into a contact.
//  - Oscillatory shear (oscillatory_shear.hpp, solver = "static"): the same set-up per
//    orientation (plates from the periodic images), the upper plate displaced by amplitude x H
//    along x'; G' = mean region stress / strain, the plate stress as the check. One cycle of
//    samples at samples_per_cycle phases is written (stress = G' x strain exactly: no phase lag
//    without inertia and damping, delta = 0 by construction).
//  - The stiffness tensor of a periodic model under affine strain (periodic boundaries along
//    x, y, z, no plates): C_IJ in Voigt notation from six solves with one factorization.
#pragma once

#include <array>
#include <istream>
#include <ostream>
#include <span>
#include <vector>

#include "packlab/core/packing.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/mechanics/oscillatory_shear.hpp"
#include "packlab/mechanics/static_solver.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"

namespace packlab::mechanics {

// The snapshots in a compression checkpoint (both solvers; uniaxial_compression.cpp).
void write_compression_snapshots(std::ostream& out, const std::vector<UniaxialCompressionSnapshot>& snapshots);
void read_compression_snapshots(std::istream& in, std::vector<UniaxialCompressionSnapshot>& snapshots);

// The snapshots a compression run owes (both solvers): the requested strains and applied
// stresses in increasing order, and how many of each have been taken.
struct PendingSnapshots {
  std::vector<double> strains, stresses;
  std::size_t next_strain = 0, next_stress = 0;
  explicit PendingSnapshots(const UniaxialCompressionOptions& options);
  bool strain_due(double strain) const { return next_strain < strains.size() && strain >= strains[next_strain]; }
  bool stress_due(double stress) const { return next_stress < stresses.size() && stress >= stresses[next_stress]; }
  UniaxialCompressionSnapshot take_strain();  // the next strain request (requested_stress NaN)
  UniaxialCompressionSnapshot take_stress();  // the next stress request (requested_strain NaN)
  // After a resume: count the snapshots taken of each kind and give each stress snapshot its
  // requested stress (a checkpoint stores a stress snapshot's requested strain as NaN, and the
  // requests are taken in increasing order); InputError when they do not fit the requests.
  void resume(std::vector<UniaxialCompressionSnapshot>& taken);
};

UniaxialCompressionResult run_static_uniaxial_compression(const Packing& bonded_model,
                                                          const UniaxialCompressionOptions& options);

// `prestress_scale` != 0: the linearization includes the geometric stiffness of the links'
// normal forces in the set-up (static_stiffness.hpp), scaled by it (1: as the engine computes
// them; 0: none, the default), and the region stress the change of the branches times those
// forces. An experiment (docs/shear.md, the check on n = 0.25, z:x; bench_static prestress), not
// a user option.
ShearRun run_static_shear_orientation(const Packing& bonded, const ShearOrientation& orientation,
                                      const OscillatoryShearOptions& options, double prestress_scale = 0.0);
// The shear stress of the static set-up for the solution q (6 per particle): shear_stress of the
// links' forces, with the pre-stress's part of the region stress when links.prestress is set.
ShearStress static_shear_stress(const StaticLinks& links, std::span<const double> q, const ShearSetup& setup,
                                int regions);

struct PeriodicStiffness {
  // Voigt order xx, yy, zz, yz, xz, xy; engineering shear strains (gamma = 2 eps), so that
  // C[4][4] is the shear modulus G_xz and, for an isotropic solid, C[0][1] = lambda.
  std::array<std::array<double, 6>, 6> stiffness{};  // [Pa]
  double bulk_modulus = 0.0;                         // Voigt average (C11 + C22 + C33 + 2 (C12 + C13 + C23)) / 9 [Pa]
  double shear_modulus = 0.0;                        // (C44 + C55 + C66) / 3 [Pa]
  std::array<double, 3> youngs_modulus{};            // 1 / S_aa along x, y, z (S = C^-1) [Pa]
  // Under uniaxial stress along a: the mean lateral contraction over the axial strain,
  // -(S_ba + S_ca) / (2 S_aa) [-].
  std::array<double, 3> poisson_ratio{};
  StaticSolverStats solver;
};
// InputError unless the box is periodic along x, y and z.
PeriodicStiffness periodic_stiffness(const Packing& model, const dem::EngineConfig& config,
                                     const StaticSolverOptions& solver = {});

}  // namespace packlab::mechanics
