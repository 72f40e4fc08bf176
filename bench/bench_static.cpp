// The quasi-static solver (docs/static-solver.md) on the papers' large cases:
//   bench_static compress [THREADS] [FILE] [BACKEND] [MAX_BREAKS] [SAVE] [CURVE] [CHECK_INTERVAL]
//     the ~54,000-particle FCC inverse opal of docs/opal.md (bench/opal_case.hpp; FILE "-"), or
//     the bonded model / particle packing in FILE: Young's modulus from one solve, then the
//     strength curve by sequential linear analysis until the test's stop rule or MAX_BREAKS
//     bond breaks (0: no limit; -1: modulus only). SAVE: write the model built to this file
//     ("-": none); CURVE: write the envelope (one row per break) to this CSV; CHECK_INTERVAL:
//     check every n-th re-solve (default: the test's, 16; 1 = each).
//   bench_static compare CSV
//     static against dynamic on small disordered models, one row per test (the data of
//     docs/static-solver.md, examples/static/compare.sh): G' of a 70 %-diluted FCC network of
//     contact bonds (touching, and with a gap of 1e-3 d; strain amplitude 1e-3 and 1e-4), and E
//     and strength of 300-particle force-biased samples with elastic bonds (seeds 1-3; eq. 16 on
//     compressed bonds too, so that the peak lies within 5 % strain).
//   bench_static shear [THREADS] [FILE] [BACKEND]
//     G' in the six orientations of the N_S = 8000 VEM structure
//     (examples/shear/data/vem_ns8000_nv2000.xyz, contact bonds at 1.01 x 2r, Table 1), already
//     relaxed: one solve per orientation.
//   bench_static prestress [THREADS] [FILE] [ORIENTATIONS] [SCALES]
//     the pre-stress hypothesis of docs/shear.md (the check on n = 0.25, z:x): the structure of
//     `bench_static shear` relaxed by §2.2 to the criterion (as `test shear`), the forces of its
//     links in the relaxed state as the engine gives them (normal force N, tension positive;
//     shear force with the relaxation's shear histories; the mean pre-stress 1/V sum N L nn),
//     then per orientation (default z:x) the normal forces of the static set-up's links and G'
//     by the static solver with the geometric stiffness of those forces scaled by each of SCALES
//     (comma-separated, default 0,0.5,1,2; 0 = the default solver), and again by an LDL^T
//     factorization (the term can make the matrix indefinite, where the solver's Cholesky
//     stops), with the number of negative eigenvalues. Then, without the term, the unbonded
//     contacts as the engine has them with friction 0: without shear stiffness, and opening when
//     their pair moves apart (G' at +/- the strain, and over the amplitudes of the dynamic
//     test's cycles).
//   bench_static orderings [FILE]
//     the factor's fill under CHOLMOD's orderings for the compression set-up of the opal (or the
//     model in FILE): why the whole strength curve takes what it takes (docs/static-solver.md).
//   bench_static model TILES PACKING OUT
//     writes the opal model built from the particle packing PACKING ("-": the default FBA packing
//     of opal_case.hpp, one tile of it about 3,400 opal particles) tiled TILES x TILES to OUT.
//   mpirun -np K bench_static petsc MODEL [THREADS] [OPTIONS]
//     (in a build with PETSc) Young's modulus of the bonded MODEL by the PETSc backend on K ranks
//     (ranks > 0 serve rank 0, as in the packlab program), PETSc OPTIONS as --petsc-options;
//     prints the unknowns, the nonzeros of the matrix and of MUMPS's factor, the seconds to
//     assemble + factorize and to solve, MUMPS's factorization memory (all ranks) and every
//     rank's peak resident memory; last line: packlab static petsc ... .
//     scripts/bench-petsc.sh runs it over growing opals (docs/data/petsc_scaling.csv).
// BACKEND: auto, cholmod, eigen or petsc. Prints the unknowns, nonzeros of the matrix and of the
// factor, bytes per bond, seconds per phase; last line: packlab static ... .
// GCC 12 reports a false -Wmaybe-uninitialized inside Eigen's AVX-512 kernels (see analyze/fits.cpp).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <fmt/format.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <string>

#include "../tests/test_packings.hpp"
#include "opal_case.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"
#include "packlab/core/thread_wait.hpp"
#include "packlab/dem/relax.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/generate/lattice.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/mechanics/opal_materials.hpp"
#include "packlab/mechanics/static_loading.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"
#ifdef PACKLAB_HAVE_PETSC
#include "packlab/mechanics/static_solver_petsc.hpp"
#endif
#include "shear_case.hpp"

using namespace packlab;
using namespace packlab::bench;

namespace {

int compress(int argc, char** argv) {
  const int threads = argc > 2 ? std::atoi(argv[2]) : 1;
  const std::string file = argc > 3 ? argv[3] : "-";
  const std::string backend = argc > 4 ? argv[4] : "auto";
  const long max_breaks = argc > 5 ? std::atol(argv[5]) : -1;
  const std::string save = argc > 6 ? argv[6] : "";
  const std::string curve_file = argc > 7 ? argv[7] : "";
  const int check_interval = argc > 8 ? std::atoi(argv[8]) : 0;  // 0: the default
  const auto t_build = std::chrono::steady_clock::now();
  const Packing model = opal_case(file, 4, threads);
  fmt::print("model: {} particles, {} bonds ({:.1f} s to read or build)\n", model.size(), model.bonds.size(),
             since(t_build));
  if (!save.empty() && save != "-") io::write_packing(model, save);

  mechanics::UniaxialCompressionSetup setup;
  setup.options.threads = threads;
  setup.finish(model);
  mechanics::UniaxialCompressionOptions o = setup.options;
  o.solver = "static";
  o.solver_backend = backend;
  o.max_breaks = max_breaks < 0 ? 1 : max_breaks;
  if (check_interval > 0) o.check_interval = check_interval;
  if (max_breaks < 0) o.max_strain = 1e-6;  // modulus only: no bond reaches its strength
  long points = 0;
  const auto t_run = std::chrono::steady_clock::now();
  o.on_point = [&](const mechanics::UniaxialCompressionPoint& p) {
    // Progress on stderr (unbuffered): a long analysis shows where it is.
    if (++points % 200 == 0)
      fmt::print(stderr, "{} breaks, strain {:.5g}, stress {:.5g} Pa, {:.1f} s\n", points - 1, p.strain, p.stress,
                 since(t_run));
  };
  const auto t0 = std::chrono::steady_clock::now();
  const mechanics::UniaxialCompressionResult r = mechanics::run_uniaxial_compression(model, o);
  const double seconds = since(t0);
  if (!curve_file.empty()) {
    std::FILE* f = std::fopen(curve_file.c_str(), "w");
    if (!f) fail_input(fmt::format("cannot write {}", curve_file));
    fmt::print(f, "break,strain,stress\n");
    for (std::size_t k = 0; k < r.curve.size(); ++k)
      fmt::print(f, "{},{:.10g},{:.10g}\n", k, r.curve[k].strain, r.curve[k].stress);
    std::fclose(f);
  }
  fmt::print(
      "E = {:.4g} Pa, strength = {:.4g} Pa at strain {:.4g}, {} bonds broken, {} solves, {} factorizations, "
      "stop: {}\n",
      r.youngs_modulus, r.strength, r.strain_at_peak, r.broken_bonds, r.solves, r.factorizations, r.stop_reason);
  fmt::print(
      "unknowns {}, matrix nonzeros {} (lower), factor nonzeros {}; assemble + factorize {:.2f} s, solves {:.2f} s "
      "(of which {} checks {:.2f} s, check_interval {}, {} rollbacks; {} PCG iterations), {} downdates {:.2f} s, "
      "set-up and links {:.2f} s\n",
      r.unknowns, r.matrix_nonzeros, r.factor_nonzeros, r.factor_seconds, r.solve_seconds, r.checks, r.check_seconds,
      o.check_interval, r.rollbacks, r.pcg_iterations, r.downdates, r.downdate_seconds,
      seconds - r.factor_seconds - r.solve_seconds - r.downdate_seconds);
  const double bytes_per_bond = static_cast<double>(r.solver_bytes) / static_cast<double>(r.bonds);
  fmt::print(
      "packlab static compress N={} bonds={} threads={} backend={} breaks={} wall_s={:.2f} "
      "solver_bytes_per_bond={:.0f}\n",
      r.particles, r.bonds, threads, backend, r.broken_bonds, seconds, bytes_per_bond);
  return 0;
}

int shear(int argc, char** argv) {
  const int threads = argc > 2 ? std::atoi(argv[2]) : 1;
  const std::string file = argc > 3 ? argv[3] : "examples/shear/data/vem_ns8000_nv2000.xyz";
  const std::string backend = argc > 4 ? argv[4] : "auto";
  Packing packing = shear_case(file);
  mechanics::OscillatoryShearOptions o;
  o.threads = threads;
  o.solver = "static";
  o.solver_backend = backend;
  o.relax = false;
  o.orientations = "all";
  const auto t0 = std::chrono::steady_clock::now();
  const mechanics::OscillatoryShearResult r = mechanics::run_oscillatory_shear(packing, o);
  const double seconds = since(t0);
  std::size_t bytes = 0;
  for (const auto& run : r.runs) {
    fmt::print("{}: G' = {:.5g} Pa (plate {:.5g} Pa), {:.2f} s\n", mechanics::orientation_name(run.orientation),
               run.storage_modulus, run.plate_storage_modulus, run.seconds);
    bytes = std::max(bytes, run.solver_bytes);
  }
  const auto& first = r.runs.front();
  fmt::print("G' mean {:.5g} Pa, SD {:.3g} Pa over {} orientations\n", r.storage_modulus_mean, r.storage_modulus_std,
             r.runs.size());
  fmt::print(
      "packlab static shear N={} bonds={} threads={} backend={} orientations={} wall_s={:.2f} "
      "solver_bytes_per_bond={:.0f}\n",
      first.structure_particles + first.plate_particles, first.bonds, threads, backend, r.runs.size(), seconds,
      static_cast<double>(bytes) / static_cast<double>(first.bonds));
  return 0;
}

// Statistics of link forces: count, tension / compression, mean and max |N|, sum |N| / L, sum
// k_n, sum k_s (links given by tension N, length L, stiffnesses).
struct ForceStats {
  std::size_t links = 0, tension = 0, compression = 0;
  double sum_abs = 0.0, max_abs = 0.0, sum_over_length = 0.0, sum_kn = 0.0, sum_ks = 0.0;
  double sum_shear = 0.0, max_shear = 0.0;
  void add(double N, double L, double kn, double ks, double shear = 0.0) {
    ++links;
    tension += N > 0.0;
    compression += N < 0.0;
    sum_abs += std::abs(N);
    max_abs = std::max(max_abs, std::abs(N));
    sum_over_length += std::abs(N) / L;
    sum_kn += kn;
    sum_ks += ks;
    sum_shear += shear;
    max_shear = std::max(max_shear, shear);
  }
  void print(const std::string& what, bool shear) const {
    const double n = static_cast<double>(std::max<std::size_t>(links, 1));
    fmt::print(
        "{}: links {} tension {} compression {} mean|N| {:.4e} N max|N| {:.4e} N sum|N|/L {:.4e} N/m sum_kn {:.4e} "
        "N/m sum_ks {:.4e} N/m ratio_kn {:.4e} ratio_ks {:.4e}",
        what, links, tension, compression, sum_abs / n, max_abs, sum_over_length, sum_kn, sum_ks,
        sum_over_length / sum_kn, sum_ks > 0.0 ? sum_over_length / sum_ks : 0.0);
    if (shear) fmt::print(" mean|Fs| {:.4e} N max|Fs| {:.4e} N", sum_shear / n, max_shear);
    fmt::print("\n");
  }
};

// G' of one orientation by an LDL^T factorization of the static set-up's matrix (Eigen's
// simplicial LDL^T, AMD ordering, no pivoting), which also takes an indefinite matrix (the
// geometric term of compressed links can make it so, where the solver's Cholesky stops). The
// negative entries of D count the matrix's negative eigenvalues (Sylvester's law of inertia).
// Also: the free particles whose own 6 x 6 block is indefinite, and the unbonded contacts that
// the solution would open (normal displacement beyond their overlap).
struct LdltShear {
  bool ok = false;
  double storage_modulus = 0.0, plate_storage_modulus = 0.0;
  long negative_pivots = 0, indefinite_blocks = 0, opening_contacts = 0, contacts = 0;
  double seconds = 0.0;
};
LdltShear ldlt_shear(const Packing& relaxed, const mechanics::ShearOrientation& orientation,
                     const mechanics::OscillatoryShearOptions& o, double scale) {
  const auto t0 = std::chrono::steady_clock::now();
  LdltShear out;
  const mechanics::ShearSetup setup =
      mechanics::build_shear_setup(mechanics::oriented_packing(relaxed, orientation), o.plate_layers, o.regions);
  mechanics::StaticLinks links =
      mechanics::linearize_links(setup.packing, mechanics::shear_engine_config(o), scale != 0.0);
  for (double& N : links.prestress) N *= scale;
  std::vector<std::uint8_t> prescribed(setup.packing.size());
  for (std::size_t k = 0; k < prescribed.size(); ++k) prescribed[k] = setup.role[k] != 0 ? 1 : 0;
  mechanics::StiffnessAssembly a(links, prescribed);
  a.assemble({}, mechanics::StaticSolverOptions{}.regularization);
  for (std::size_t p = 0; p < a.unknowns() / 6; ++p) {
    Eigen::Matrix<double, 6, 6> block;
    for (int c = 0; c < 6; ++c)
      for (int r = c; r < 6; ++r)
        block(r, c) = block(c, r) = a.values()[static_cast<std::size_t>(a.column_start()[6 * p + c] + (r - c))];
    // Below -1e-9 x the largest eigenvalue (zero modes come out at roundoff).
    const auto eig = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>(block).eigenvalues();
    out.indefinite_blocks += eig(0) < -1e-9 * eig(5);
  }
  std::vector<double> q(6 * setup.packing.size(), 0.0);
  for (std::size_t k = 0; k < prescribed.size(); ++k)
    if (setup.role[k] == 2) q[6 * k] = o.amplitude * setup.height;
  const std::vector<double> f = a.load(q, {}, {});
  const auto n = static_cast<Eigen::Index>(a.unknowns());
  const Eigen::Map<const Eigen::SparseMatrix<double, Eigen::ColMajor, int>> K(
      n, n, static_cast<Eigen::Index>(a.values().size()), a.column_start().data(), a.row().data(), a.values().data());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double, Eigen::ColMajor, int>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt(
      K);
  if (ldlt.info() != Eigen::Success) return out;
  for (Eigen::Index k = 0; k < n; ++k) out.negative_pivots += ldlt.vectorD()(k) < 0.0;
  std::vector<double> x(a.unknowns());
  Eigen::Map<Eigen::VectorXd>(x.data(), n) = ldlt.solve(Eigen::Map<const Eigen::VectorXd>(f.data(), n));
  a.scatter(x, q);
  const mechanics::ShearStress st = mechanics::static_shear_stress(links, q, setup, o.regions);
  out.storage_modulus = st.stress / o.amplitude;
  out.plate_storage_modulus = st.plate_stress / o.amplitude;
  for (std::size_t k = 0; k < links.size(); ++k) {
    if (links.bond[k] >= 0 ||
        (prescribed[static_cast<std::size_t>(links.i[k])] && prescribed[static_cast<std::size_t>(links.j[k])]))
      continue;
    ++out.contacts;
    out.opening_contacts += mechanics::link_response(links, k, q, {}).normal_displacement > links.geometry[k].overlap;
  }
  out.ok = true;
  out.seconds = since(t0);
  return out;
}

// A side check of the same set-up (no pre-stress term): the unbonded contacts. The relaxed
// contacts overlap by |N| / k_n, far less than the relative displacements of the test, so in the
// dynamic test a contact whose pair moves apart opens; and with friction 0 (Table 1) the engine's
// contact carries no shear force, where the linearization takes it as sticking (k_s).
// `frictionless`: the unbonded contacts without k_s. `sign` 0: every unbonded contact kept;
// 2: every one with a free end left out; +1 / -1: the upper plate moved by +/- amplitude x H and
// the contacts that the solution opens (normal displacement beyond their overlap) left out, again
// until no open contact closes and no closed one opens (at most 30 rounds; G' of the last 10
// rounds as min and max when it has not settled).
struct ContactShear {
  double storage_modulus = 0.0, plate_storage_modulus = 0.0;
  double last_min = 0.0, last_max = 0.0;
  long contacts = 0, open = 0, rounds = 0, flips = 0;
};
ContactShear contact_shear(const Packing& relaxed, const mechanics::ShearOrientation& orientation,
                           const mechanics::OscillatoryShearOptions& o, int sign, bool frictionless, double amplitude) {
  const mechanics::ShearSetup setup =
      mechanics::build_shear_setup(mechanics::oriented_packing(relaxed, orientation), o.plate_layers, o.regions);
  mechanics::StaticLinks links = mechanics::linearize_links(setup.packing, mechanics::shear_engine_config(o));
  std::vector<std::uint8_t> prescribed(setup.packing.size());
  for (std::size_t k = 0; k < prescribed.size(); ++k) prescribed[k] = setup.role[k] != 0 ? 1 : 0;
  ContactShear out;
  std::vector<std::uint8_t> contact(links.size(), 0), open(links.size(), 0);
  for (std::size_t k = 0; k < links.size(); ++k) {
    const bool free =
        !prescribed[static_cast<std::size_t>(links.i[k])] || !prescribed[static_cast<std::size_t>(links.j[k])];
    if (links.bond[k] >= 0 || !free) continue;
    contact[k] = 1;
    ++out.contacts;
    if (frictionless) links.stiffness[k].shear = 0.0;
    if (sign == 2) open[k] = 1;
  }
  const double strain = sign == -1 ? -amplitude : amplitude;
  std::vector<double> history;
  for (;;) {
    ++out.rounds;
    mechanics::StaticLinks l = links;
    for (std::size_t k = 0; k < l.size(); ++k)
      if (open[k]) l.stiffness[k] = {};
    std::vector<double> q(6 * setup.packing.size(), 0.0);
    for (std::size_t k = 0; k < prescribed.size(); ++k)
      if (setup.role[k] == 2) q[6 * k] = strain * setup.height;
    mechanics::StaticSolver solver(l, prescribed, {});
    solver.solve(q, {});
    const mechanics::ShearStress st = mechanics::static_shear_stress(l, q, setup, o.regions);
    out.storage_modulus = st.stress / strain;
    out.plate_storage_modulus = st.plate_stress / strain;
    history.push_back(out.storage_modulus);
    out.open = 0;
    for (std::size_t k = 0; k < links.size(); ++k) out.open += open[k];
    if (sign != 1 && sign != -1) break;
    out.flips = 0;
    for (std::size_t k = 0; k < links.size(); ++k) {
      if (!contact[k]) continue;
      // The pair's normal displacement (the same kinematics with the contact's stiffness back).
      const bool opens = mechanics::link_response(links, k, q, {}).normal_displacement > links.geometry[k].overlap;
      out.flips += opens != (open[k] != 0);
      open[k] = opens ? 1 : 0;
    }
    if (out.flips == 0 || out.rounds >= 30) break;
  }
  const std::size_t first = history.size() > 10 ? history.size() - 10 : 0;
  out.last_min = *std::min_element(history.begin() + static_cast<std::ptrdiff_t>(first), history.end());
  out.last_max = *std::max_element(history.begin() + static_cast<std::ptrdiff_t>(first), history.end());
  return out;
}

int prestress(int argc, char** argv) {
  const int threads = argc > 2 ? std::atoi(argv[2]) : 1;
  const std::string file = argc > 3 ? argv[3] : "examples/shear/data/vem_ns8000_nv2000.xyz";
  const std::string orientations = argc > 4 ? argv[4] : "z:x";
  const std::string scale_list = argc > 5 ? argv[5] : "0,0.5,1,2";
  std::vector<double> scales;
  for (std::size_t at = 0; at <= scale_list.size();) {
    const std::size_t comma = std::min(scale_list.find(',', at), scale_list.size());
    scales.push_back(std::stod(scale_list.substr(at, comma - at)));
    at = comma + 1;
  }
  const Packing packing = shear_case(file);
  mechanics::OscillatoryShearOptions o;  // Table 1, as examples/shear/table2_small.toml
  o.threads = threads;
  o.solver = "static";
  o.relax = false;
  o.orientations = orientations;
  const dem::EngineConfig config = mechanics::shear_engine_config(o);

  // The §2.2 relaxation as relax_bonded does it (default criterion, at most 100000 steps),
  // keeping the engine for the forces with their shear histories.
  const auto t0 = std::chrono::steady_clock::now();
  dem::Engine engine(packing, config);
  const dem::ZeroVelocityRelaxResult relax = dem::relax_zeroing_velocities(engine, o.relax_options);
  Packing relaxed = engine.packing();
  relaxed.velocity.clear();
  relaxed.angular_velocity.clear();
  fmt::print(
      "structure: {} particles, {} bonds; relaxation {} steps, converged {}, <|F_i|> {:.4e} -> {:.4e} N, {:.1f} s\n",
      packing.size(), packing.bonds.size(), relax.steps, relax.converged, relax.initial_unbalanced_force,
      relax.final_unbalanced_force, since(t0));

  // The relaxed periodic structure's links as the engine gives them.
  const dem::ContactForces f = engine.contact_forces();
  const auto& bond_params = std::get<dem::BondMaterialList<dem::ContactBond>>(config.bond_materials).front();
  const double contact_kn = 0.5 * o.normal_stiffness, contact_ks = 0.5 * o.shear_stiffness;  // particle rule
  ForceStats bonds, contacts, all;
  double sigma[3][3] = {}, sigma_normal[3][3] = {};
  std::vector<Vec3> resultant(relaxed.size()), resultant_normal(relaxed.size());
  for (std::size_t c = 0; c < f.size(); ++c) {
    if (f.j[c] < 0) continue;
    const Vec3& d = f.branch[c];
    const double L = norm(d);
    const Vec3 n = d * (1.0 / L);
    const Vec3& F = f.force[c];
    const double N = -dot(F, n);
    const double shear = norm(F + N * n);
    const bool bond = f.kind[c] == dem::ContactForces::bond;
    const double kn = bond ? bond_params.normal_stiffness : contact_kn;
    const double ks = bond ? bond_params.shear_stiffness : contact_ks;
    (bond ? bonds : contacts).add(N, L, kn, ks, shear);
    all.add(N, L, kn, ks, shear);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        sigma[a][b] -= d[a] * F[b];
        sigma_normal[a][b] += N * L * n[a] * n[b];
      }
    const auto i = static_cast<std::size_t>(f.i[c]), j = static_cast<std::size_t>(f.j[c]);
    resultant[j] += F;
    resultant[i] -= F;
    resultant_normal[j] -= N * n;
    resultant_normal[i] += N * n;
  }
  bonds.print("relaxed bonds", true);
  contacts.print("relaxed contacts", true);
  all.print("relaxed all", true);
  const double volume = relaxed.box.volume();
  fmt::print(
      "mean pre-stress 1/V sum -d (x) F [Pa] (tension positive), xx yy zz yz xz xy: {:.4e} {:.4e} {:.4e} {:.4e} "
      "{:.4e} {:.4e}\n",
      sigma[0][0] / volume, sigma[1][1] / volume, sigma[2][2] / volume, sigma[1][2] / volume, sigma[0][2] / volume,
      sigma[0][1] / volume);
  fmt::print("the same from the normal forces alone, 1/V sum N L nn [Pa]: {:.4e} {:.4e} {:.4e} {:.4e} {:.4e} {:.4e}\n",
             sigma_normal[0][0] / volume, sigma_normal[1][1] / volume, sigma_normal[2][2] / volume,
             sigma_normal[1][2] / volume, sigma_normal[0][2] / volume, sigma_normal[0][1] / volume);
  double sum_resultant = 0.0, sum_resultant_normal = 0.0;
  for (std::size_t p = 0; p < relaxed.size(); ++p) {
    sum_resultant += norm(resultant[p]);
    sum_resultant_normal += norm(resultant_normal[p]);
  }
  const double np = static_cast<double>(relaxed.size());
  fmt::print("mean |resultant| per particle [N]: all forces {:.4e}, normal forces alone {:.4e} (mean |N| {:.4e})\n",
             sum_resultant / np, sum_resultant_normal / np, all.sum_abs / static_cast<double>(all.links));

  std::fflush(stdout);
  for (const auto& orientation : mechanics::shear_orientations(orientations)) {
    const std::string name = mechanics::orientation_name(orientation);
    // The static set-up's links with their normal forces (as run_static_shear_orientation builds them).
    const mechanics::ShearSetup setup =
        mechanics::build_shear_setup(mechanics::oriented_packing(relaxed, orientation), o.plate_layers, o.regions);
    const mechanics::StaticLinks links = mechanics::linearize_links(setup.packing, config, true);
    ForceStats s;
    for (std::size_t k = 0; k < links.size(); ++k)
      s.add(links.prestress[k], norm(links.branch[k]), links.stiffness[k].normal, links.stiffness[k].shear);
    s.print(fmt::format("{} set-up links", name), false);
    std::fflush(stdout);
    for (double scale : scales) {
      // The static solver as `test shear --solver static` runs it (Cholesky: positive definite only).
      try {
        const mechanics::ShearRun run = mechanics::run_static_shear_orientation(relaxed, orientation, o, scale);
        fmt::print("{} prestress_scale {:g} solver: G' = {:.10g} Pa (plate {:.10g} Pa), {:.2f} s\n", name, scale,
                   run.storage_modulus, run.plate_storage_modulus, run.seconds);
      } catch (const InputError& e) {
        fmt::print("{} prestress_scale {:g} solver: failed: {}\n", name, scale, e.what());
      }
      std::fflush(stdout);
      const LdltShear l = ldlt_shear(relaxed, orientation, o, scale);
      if (l.ok)
        fmt::print(
            "{} prestress_scale {:g} ldlt: G' = {:.10g} Pa (plate {:.10g} Pa), negative pivots {}, indefinite particle "
            "blocks {}, contacts opened {} of {}, {:.2f} s\n",
            name, scale, l.storage_modulus, l.plate_storage_modulus, l.negative_pivots, l.indefinite_blocks,
            l.opening_contacts, l.contacts, l.seconds);
      else
        fmt::print("{} prestress_scale {:g} ldlt: factorization failed\n", name, scale);
      std::fflush(stdout);
    }
    // The unbonded contacts (no pre-stress term).
    for (const bool frictionless : {false, true})
      for (const int sign : {0, 2, 1, -1}) {
        if (sign == 0 && !frictionless) continue;  // the solver's G' above
        const ContactShear c = contact_shear(relaxed, orientation, o, sign, frictionless, o.amplitude);
        const char* what[] = {"bilateral", "left out", "unilateral +strain", "unilateral -strain"};
        fmt::print(
            "{} contacts {} {}: G' = {:.7g} Pa (plate {:.7g} Pa), open {} of {} unbonded contacts with a free end, "
            "{} rounds, {} changed in the last, G' of the last 10 rounds {:.7g} ... {:.7g} Pa\n",
            name, frictionless ? "frictionless" : "sticking",
            what[sign == 0   ? 0
                 : sign == 2 ? 1
                 : sign == 1 ? 2
                             : 3],
            c.storage_modulus, c.plate_storage_modulus, c.open, c.contacts, c.rounds, c.flips, c.last_min, c.last_max);
        std::fflush(stdout);
      }
    // The dynamic test's cycles c = 1 .. cycles have the amplitudes c / cycles x amplitude, and
    // its G' is the mean of theirs; for a response of slope G+ at positive and G- at negative
    // strain the sine's coefficient is (G+ + G-) / 2. The same with the frictionless unilateral
    // contacts at each amplitude.
    double mean = 0.0;
    for (int cycle = 1; cycle <= o.cycles; ++cycle) {
      const double amplitude = o.amplitude * cycle / o.cycles;
      const ContactShear plus = contact_shear(relaxed, orientation, o, 1, true, amplitude);
      const ContactShear minus = contact_shear(relaxed, orientation, o, -1, true, amplitude);
      const double g = 0.5 * (plus.storage_modulus + minus.storage_modulus);
      mean += g / o.cycles;
      fmt::print(
          "{} contacts frictionless unilateral amplitude {:.4g}: G+ = {:.7g} Pa, G- = {:.7g} Pa, (G+ + G-) / 2 = "
          "{:.7g} Pa (plate {:.7g} Pa), open {} and {}, rounds {} and {}, changed in the last {} and {}\n",
          name, amplitude, plus.storage_modulus, minus.storage_modulus, g,
          0.5 * (plus.plate_storage_modulus + minus.plate_storage_modulus), plus.open, minus.open, plus.rounds,
          minus.rounds, plus.flips, minus.flips);
      std::fflush(stdout);
    }
    fmt::print("{} contacts frictionless unilateral, mean over the {} amplitudes: G' = {:.7g} Pa\n", name, o.cycles,
               mean);
  }
  fmt::print("packlab static prestress N={} threads={} orientations={} scales={} wall_s={:.2f}\n", packing.size(),
             threads, orientations, scale_list, since(t0));
  return 0;
}

int compare(int argc, char** argv) {
  if (argc < 3) {
    fmt::print(stderr, "usage: bench_static compare CSV\n");
    return 2;
  }
  std::string csv = "model,variant,orientation,solver,quantity,value,seconds\n";
  auto row = [&](const std::string& model, const std::string& variant, const std::string& orientation,
                 const std::string& solver, const std::string& quantity, double value, double seconds) {
    csv += fmt::format("{},{},{},{},{},{:.8g},{:.3f}\n", model, variant, orientation, solver, quantity, value, seconds);
    fmt::print("{} {} {} {} {} = {:.6g} ({:.2f} s)\n", model, variant, orientation, solver, quantity, value, seconds);
  };
  // G' of a diluted FCC network of contact bonds.
  const double r0 = 0.25e-6;
  for (const double gap : {0.0, 1e-3}) {
    generate::LatticeParams lp;
    lp.type = generate::LatticeType::fcc;
    lp.cells = {3, 3, 3};
    lp.radius = r0;
    lp.gap = gap * 2 * r0;
    Packing p = generate::make_lattice(lp);
    generate::BondingOptions bo;
    bo.cutoff_ratio = 1.01;
    generate::add_bonds(p, bo);
    Bonds kept;
    Random rng(7);
    for (std::size_t b = 0; b < p.bonds.size(); ++b)
      if (rng.uniform() < 0.7) kept.add(p.bonds.i[b], p.bonds.j[b], p.bonds.image[b], 0, p.bonds.rest_length[b]);
    p.bonds = kept;
    for (const double amplitude : {1e-3, 1e-4})
      for (const std::string solver : {"dynamic", "static"}) {
        mechanics::OscillatoryShearOptions o;
        o.stiffness_rule = "contact";
        o.normal_strength = o.shear_strength = std::numeric_limits<double>::infinity();
        o.cycles = 2;
        o.steps_per_cycle = 4000;
        o.orientations = "z:x,x:y";
        o.threads = 1;
        o.amplitude = amplitude;
        o.solver = solver;
        const mechanics::OscillatoryShearResult r = mechanics::run_oscillatory_shear(p, o);
        for (const auto& run : r.runs)
          row("diluted_fcc", fmt::format("gap={:g}d amplitude={:g}", gap, amplitude),
              mechanics::orientation_name(run.orientation), solver, "storage_modulus", run.storage_modulus,
              run.seconds);
      }
  }
  // E and strength of force-biased samples, elastic bonds (silica), the automatic quasi-static rate.
  for (const unsigned seed : {1u, 2u, 3u}) {
    const Packing p = test::random_bonded_sample(300, seed, 7.5e-9);  // the tests' sample
    mechanics::UniaxialCompressionSetup setup;
    setup.options.threads = 1;
    setup.options.max_strain = 0.05;
    setup.options.samples = 300;
    setup.finish(p);
    // Eq. 16 on compressed bonds too: the sample then passes its peak (about 2 % strain) well
    // before max_strain; with stretched bonds only it is still hardening at 5 %.
    for (auto& b : setup.options.bond_materials) b.compressive_breakage = true;
    for (const std::string solver : {"dynamic", "static"}) {
      setup.options.solver = solver;
      const mechanics::UniaxialCompressionResult r = mechanics::run_uniaxial_compression(p, setup.options);
      const std::string variant = fmt::format("seed={}", seed);
      row("fba300_elastic", variant, "z", solver, "youngs_modulus", r.youngs_modulus, r.seconds);
      row("fba300_elastic", variant, "z", solver, "strength", r.strength, r.seconds);
      row("fba300_elastic", variant, "z", solver, "strain_at_peak", r.strain_at_peak, r.seconds);
      row("fba300_elastic", variant, "z", solver, "broken_bonds", static_cast<double>(r.broken_bonds), r.seconds);
    }
  }
  std::FILE* f = std::fopen(argv[2], "w");
  if (!f) return 2;
  std::fputs(csv.c_str(), f);
  std::fclose(f);
  return 0;
}

int model(int argc, char** argv) {
  if (argc < 5) fail_input("bench_static model TILES PACKING OUT");
  const int tiles = std::atoi(argv[2]);
  const std::string packing = argv[3];
  const Packing input = packing == "-" ? default_packing(1) : io::read_packing(packing);
  const Packing m = make_opal(tile(input, tiles), 1);
  io::write_packing(m, argv[4]);
  return 0;
}

#ifdef PACKLAB_HAVE_PETSC
int petsc(int argc, char** argv) {
  if (argc < 3) fail_input("bench_static petsc MODEL [THREADS] [OPTIONS]");
  const int threads = argc > 3 ? std::atoi(argv[3]) : 1;
  const Packing m = io::read_packing(argv[2]);
  mechanics::UniaxialCompressionSetup setup;
  setup.options.threads = threads;
  setup.finish(m);
  mechanics::UniaxialCompressionOptions o = setup.options;
  o.solver = "static";
  o.solver_backend = "petsc";
  o.petsc_options = argc > 4 ? argv[4] : "";
  o.max_breaks = 1;
  o.max_strain = 1e-6;  // modulus only: no bond reaches its strength
  const auto t0 = std::chrono::steady_clock::now();
  const mechanics::UniaxialCompressionResult r = mechanics::run_uniaxial_compression(m, o);
  const double seconds = since(t0);
  const std::vector<double> memory = mechanics::petsc::peak_memory_per_rank();
  std::string per_rank;
  for (const double bytes : memory) per_rank += fmt::format("{}{:.1f}", per_rank.empty() ? "" : ",", bytes / 1048576.0);
  fmt::print(
      "E = {:.6g} Pa; unknowns {}, matrix nonzeros {} (lower), factor nonzeros {}; assemble + factorize {:.2f} s, "
      "solves {:.2f} s; matrix (rank 0) + MUMPS's factorization memory (all ranks) {:.0f} MB; peak resident MiB "
      "per rank {}\n",
      r.youngs_modulus, r.unknowns, r.matrix_nonzeros, r.factor_nonzeros, r.factor_seconds, r.solve_seconds,
      static_cast<double>(r.solver_bytes) / 1e6, per_rank);
  fmt::print(
      "packlab static petsc N={} bonds={} ranks={} threads={} unknowns={} matrix_nnz={} factor_nnz={} "
      "factor_s={:.2f} solve_s={:.2f} wall_s={:.2f} E={:.8g} rss_mib={}\n",
      r.particles, r.bonds, mechanics::petsc::ranks(), threads, r.unknowns, r.matrix_nonzeros, r.factor_nonzeros,
      r.factor_seconds, r.solve_seconds, seconds, r.youngs_modulus, per_rank);
  return 0;
}
#endif

}  // namespace

// The fill of CHOLMOD's orderings on the compression set-up of a model (mechanics::ordering_fill,
// docs/static-solver.md).
int orderings(int argc, char** argv) {
  const Packing model = opal_case(argc > 2 ? argv[2] : "-", 4, 1);
  mechanics::UniaxialCompressionSetup setup;
  setup.finish(model);
  mechanics::UniaxialCompressionResult info;
  const mechanics::UniaxialCompressionSpecimen specimen =
      mechanics::prepare_uniaxial_compression(model, setup.options, info);
  const mechanics::StaticLinks links =
      mechanics::linearize_links(specimen.model, mechanics::compression_engine_config(setup.options));
  mechanics::StiffnessAssembly a(links, specimen.model.fixed);
  a.assemble({}, 1e-12);
  fmt::print("unknowns {}, matrix nonzeros {} (lower)\n", a.unknowns(), a.values().size());
  const std::vector<mechanics::OrderingFill> fills = mechanics::ordering_fill(a);
  if (fills.empty()) {
    fmt::print(stderr, "bench_static orderings: this build has no CHOLMOD\n");
    return 2;
  }
  for (const mechanics::OrderingFill& f : fills)
    fmt::print("{:<28} factor nonzeros {:.4g}, flops {:.4g}, {:.2f} s\n", f.name, f.factor_nonzeros, f.flops,
               f.seconds);
  return 0;
}

int main(int argc, char** argv) {
  ensure_passive_thread_wait(argv);  // as the packlab program does (core/thread_wait.hpp)
#ifdef PACKLAB_HAVE_PETSC
  int worker_exit = 0;
  if (mechanics::petsc::serve_if_worker(worker_exit)) return worker_exit;
  struct ReleaseWorkers {
    ~ReleaseWorkers() { mechanics::petsc::finish(); }
  } release_workers;
#endif
  const std::string what = argc > 1 ? argv[1] : "compress";
  if (what == "model") return model(argc, argv);
#ifdef PACKLAB_HAVE_PETSC
  if (what == "petsc") return petsc(argc, argv);
#endif
  if (what == "shear") return shear(argc, argv);
  if (what == "prestress") return prestress(argc, argv);
  if (what == "orderings") return orderings(argc, argv);
  if (what == "compare") return compare(argc, argv);
  return compress(argc, argv);
}
