// The shear test with the quasi-static solver, and the stiffness tensor of a periodic model
// under affine strain (static_loading.hpp).
// GCC 12 reports a false -Wmaybe-uninitialized inside Eigen's AVX-512 kernels (see analyze/fits.cpp).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <fmt/format.h>

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <numbers>

#include "packlab/core/error.hpp"
#include "packlab/mechanics/static_loading.hpp"

namespace packlab::mechanics {

ShearStress static_shear_stress(const StaticLinks& links, std::span<const double> q, const ShearSetup& setup,
                                int regions) {
  const DisplacementGradient no_gradient{};
  ShearStress st = shear_stress(link_forces(links, q, no_gradient), setup, regions);
  if (!links.prestress.empty()) {
    // The region stress is the virial of the current state, 1/2 sum l (x) F: its increment is
    // l (x) dF (above, the pre-force's turn included) + dl (x) F0, the pre-forces F0 = -N n on
    // j times the change of the branches dl = u_j - u_i. The plate force has no such part.
    dem::ContactForces turned;
    for (std::size_t k = 0; k < links.size(); ++k) {
      if (links.prestress[k] == 0.0) continue;
      const auto i = static_cast<std::size_t>(links.i[k]), j = static_cast<std::size_t>(links.j[k]);
      turned.i.push_back(links.i[k]);
      turned.j.push_back(links.j[k]);
      turned.kind.push_back(dem::ContactForces::contact);  // not counted as a bond's load
      turned.branch.push_back(Vec3{q[6 * j] - q[6 * i], q[6 * j + 1] - q[6 * i + 1], q[6 * j + 2] - q[6 * i + 2]});
      turned.force.push_back(-links.prestress[k] / norm(links.branch[k]) * links.branch[k]);
    }
    const ShearStress extra = shear_stress(turned, setup, regions);
    for (std::size_t r = 0; r < st.region_stress.size(); ++r) st.region_stress[r] += extra.region_stress[r];
    st.stress += extra.stress;
  }
  return st;
}

ShearRun run_static_shear_orientation(const Packing& bonded, const ShearOrientation& orientation,
                                      const OscillatoryShearOptions& options, double prestress_scale) {
  validate(options);
  const auto t0 = std::chrono::steady_clock::now();
  ShearRun run;
  run.orientation = orientation;
  run.solver = "static";
  const ShearSetup setup =
      build_shear_setup(oriented_packing(bonded, orientation), options.plate_layers, options.regions);
  run.structure_particles = setup.structure;
  run.plate_particles = setup.lower + setup.upper;
  run.bonds = setup.packing.bonds.size();
  const dem::EngineConfig config = shear_engine_config(options);
  StaticLinks links = linearize_links(setup.packing, config, prestress_scale != 0.0);
  for (double& N : links.prestress) N *= prestress_scale;
  std::vector<std::uint8_t> prescribed(setup.packing.size());
  for (std::size_t k = 0; k < prescribed.size(); ++k) prescribed[k] = setup.role[k] != 0 ? 1 : 0;
  StaticSolverOptions solver_options;
  solver_options.backend = options.solver_backend;
  solver_options.petsc_options = options.petsc_options;
  solver_options.threads = options.threads;
  StaticSolver solver(links, prescribed, solver_options);

  // The upper plate displaced by the test's largest deflection along x'.
  const double strain = options.amplitude;
  std::vector<double> q(6 * setup.packing.size(), 0.0);
  for (std::size_t k = 0; k < prescribed.size(); ++k)
    if (setup.role[k] == 2) q[6 * k] = strain * setup.height;
  const DisplacementGradient no_gradient{};
  solver.solve(q, no_gradient);
  const ShearStress st = static_shear_stress(links, q, setup, options.regions);
  double energy = 0.0;
  for (std::size_t k = 0; k < links.size(); ++k) energy += link_response(links, k, q, no_gradient).energy;

  // One cycle of samples, every quantity proportional to sin(phase).
  for (int s = 1; s <= options.samples_per_cycle; ++s) {
    const double phase = 2.0 * std::numbers::pi * s / options.samples_per_cycle;
    const double f = std::sin(phase);
    ShearSample x;
    x.cycle = 1;
    x.step = s;
    x.phase = phase;
    x.strain = f * strain;
    x.stress = f * st.stress;
    x.plate_stress = f * st.plate_stress;
    for (double r : st.region_stress) x.region_stress.push_back(f * r);
    x.strain_energy = f * f * energy;
    run.samples.push_back(std::move(x));
  }
  run.cycles.push_back(evaluate_cycle(run.samples, 1));
  const ShearCycle& c = run.cycles.front();
  run.storage_modulus = c.storage_modulus;
  run.complex_modulus = c.complex_modulus;
  run.phase_angle = c.phase_angle;
  run.plate_storage_modulus = c.plate_storage_modulus;
  run.max_bond_tension = st.max_bond_tension;
  run.max_bond_shear_force = st.max_bond_shear_force;
  run.max_bond_tension_ratio = run.max_bond_tension / options.normal_strength;
  run.max_bond_shear_ratio = run.max_bond_shear_force / options.shear_strength;
  run.steps = solver.stats().solves;
  run.solver_bytes = solver.stats().matrix_bytes + solver.stats().factor_bytes;
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

PeriodicStiffness periodic_stiffness(const Packing& model, const dem::EngineConfig& config,
                                     const StaticSolverOptions& solver_options) {
  if (!(model.box.periodic[0] && model.box.periodic[1] && model.box.periodic[2]))
    fail_input("stiffness tensor: the model's box must be periodic along x, y and z");
  const StaticLinks links = linearize_links(model, config);
  if (links.size() == 0) fail_input("stiffness tensor: the model has no bonds and no touching pairs");
  const std::vector<std::uint8_t> prescribed(model.size(), 0);  // translations: see static_solver.hpp
  StaticSolver solver(links, prescribed, solver_options);
  const double volume = model.box.volume();
  // Voigt pairs: xx, yy, zz, yz, xz, xy.
  constexpr int voigt[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  PeriodicStiffness out;
  std::vector<double> q(6 * model.size());
  for (int I = 0; I < 6; ++I) {
    DisplacementGradient gradient{};
    const auto a = static_cast<std::size_t>(voigt[I][0]), b = static_cast<std::size_t>(voigt[I][1]);
    if (a == b) {
      gradient[a][a] = 1.0;
    } else {  // engineering shear strain 1: eps_ab = eps_ba = 1/2
      gradient[a][b] = 0.5;
      gradient[b][a] = 0.5;
    }
    std::fill(q.begin(), q.end(), 0.0);
    solver.solve(q, gradient);
    // sigma = -1/V sum d (x) F_j (tension positive), symmetrized.
    double sigma[3][3] = {};
    for (std::size_t k = 0; k < links.size(); ++k) {
      const Vec3 F = link_response(links, k, q, gradient).force_on_j;
      const Vec3& d = links.branch[k];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) sigma[r][c] -= d[r] * F[c] / volume;
    }
    for (int J = 0; J < 6; ++J) {
      const int r = voigt[J][0], c = voigt[J][1];
      out.stiffness[static_cast<std::size_t>(J)][static_cast<std::size_t>(I)] = 0.5 * (sigma[r][c] + sigma[c][r]);
    }
  }
  const auto& C = out.stiffness;
  out.bulk_modulus = (C[0][0] + C[1][1] + C[2][2] + 2.0 * (C[0][1] + C[0][2] + C[1][2])) / 9.0;
  out.shear_modulus = (C[3][3] + C[4][4] + C[5][5]) / 3.0;
  Eigen::Matrix<double, 6, 6> m;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) m(r, c) = C[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
  const Eigen::Matrix<double, 6, 6> S = m.inverse();
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    out.youngs_modulus[static_cast<std::size_t>(a)] = 1.0 / S(a, a);
    out.poisson_ratio[static_cast<std::size_t>(a)] = -(S(b, a) + S(c, a)) / (2.0 * S(a, a));
  }
  out.solver = solver.stats();
  return out;
}

}  // namespace packlab::mechanics
