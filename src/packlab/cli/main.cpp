// packlab: generate, analyze, build and load-test sphere packings.
// Bad input prints one line "packlab: error: ..." and exits with code 2.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "packlab/cli/commands.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/thread_wait.hpp"
#include "packlab/io/report.hpp"
#ifdef PACKLAB_HAVE_PETSC
#include "packlab/mechanics/static_solver_petsc.hpp"
#endif

int main(int argc, char** argv) {
  packlab::ensure_passive_thread_wait(argv);
#ifdef PACKLAB_HAVE_PETSC
  // Under mpirun/srun: ranks > 0 serve the static solver's PETSc backend for rank 0, which runs
  // the command (mechanics/static_solver_petsc.hpp); rank 0 releases them on its way out.
  int worker_exit = 0;
  if (packlab::mechanics::petsc::serve_if_worker(worker_exit)) return worker_exit;
  struct ReleaseWorkers {
    ~ReleaseWorkers() { packlab::mechanics::petsc::finish(); }
  } release_workers;
#endif
  CLI::App app{"packlab: random sphere packings, their microstructure and DEM load tests", "packlab"};
  app.set_version_flag("--version", fmt::format("packlab {}", packlab::io::version()));
  app.require_subcommand(1);
  auto* generate = app.add_subcommand("generate", "Generate a packing");
  generate->require_subcommand(1);
  packlab::cli::add_generate_lattice(*generate);
  packlab::cli::add_generate_random(*generate);
  packlab::cli::add_generate_vem(*generate);
  packlab::cli::add_info(app);
  packlab::cli::add_convert(app);
  packlab::cli::add_relax(app);
  // Further subcommands register here, one line each (their files are in src/packlab/cli/).
  packlab::cli::add_generate_ls(*generate);
  packlab::cli::add_generate_scrm(*generate);
  packlab::cli::add_shake(app);
  auto* analyze = packlab::cli::add_analyze(app);
  packlab::cli::add_analyze_rdf(*analyze);
  packlab::cli::add_generate_fba(*generate);
  packlab::cli::add_generate_bd(*generate);
  packlab::cli::add_bond(app);
  packlab::cli::add_config_keys(app);
  auto* build = app.add_subcommand("build", "Build a model from a packing (inverse opal)");
  build->require_subcommand(1);
  packlab::cli::add_build_opal(*build);
  auto* test = app.add_subcommand("test", "Load-test a bonded model (oscillatory shear, uniaxial compression)");
  test->require_subcommand(1);
  packlab::cli::add_test_shear(*test);
  packlab::cli::add_test_compress(*test);
  auto* calibrate = app.add_subcommand("calibrate", "Calibrate model parameters to a measured target");
  calibrate->require_subcommand(1);
  packlab::cli::add_calibrate_shear(*calibrate);
  packlab::cli::add_calibrate_compress(*calibrate);
  packlab::cli::add_study(app);
  // CLI11 says only "A subcommand is required" for a misspelt one: name it and list the known.
  if (argc > 1 && argv[1][0] != '-') {
    std::string known;
    bool found = false;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      found = found || sub->get_name() == argv[1];
      known += (known.empty() ? "" : ", ") + sub->get_name();
    }
    if (!found) {
      std::fprintf(stderr, "packlab: error: unknown subcommand '%s': must be one of %s\n", argv[1], known.c_str());
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "packlab: error: %s\n", e.what());
    return 2;
  } catch (const packlab::InputError& e) {
    std::fprintf(stderr, "packlab: error: %s\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    // A size the estimates let through, or a machine short of free memory: the input's fault
    // more than the program's, and nothing was half-written (outputs are atomic).
    std::fprintf(stderr,
                 "packlab: error: out of memory: the problem is too large for the free memory of this machine; "
                 "use fewer particles or a larger machine\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "packlab: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
