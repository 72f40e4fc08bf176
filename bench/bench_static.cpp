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
#include <fmt/format.h>

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
  if (what == "compare") return compare(argc, argv);
  return compress(argc, argv);
}
