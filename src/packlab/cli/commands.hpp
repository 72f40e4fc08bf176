// The packlab command line: one file per subcommand, each adding itself to the app.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace packlab::cli {

// Options every subcommand shares.
struct CommonOptions {
  bool quiet = false;
};

void add_generate_lattice(CLI::App& generate);
void add_generate_random(CLI::App& generate);
void add_generate_vem(CLI::App& generate);
void add_info(CLI::App& app);
void add_convert(CLI::App& app);
void add_relax(CLI::App& app);
CLI::App* add_analyze(CLI::App& app);
// LS growth, shaking, SCRM, RDF (add_analyze_rdf adds `rdf` to the analyze command).
void add_generate_ls(CLI::App& generate);
void add_generate_scrm(CLI::App& generate);
void add_shake(CLI::App& app);
void add_analyze_rdf(CLI::App& analyze);
// Bonded models and mechanical tests: `bond`, `build opal`, `generate fba`,
// `test shear|compress`, `calibrate shear|compress`.
void add_bond(CLI::App& app);
void add_generate_fba(CLI::App& generate);
// Brownian-dynamics coagulation with the DLVO potential: `generate bd`.
void add_generate_bd(CLI::App& generate);
void add_build_opal(CLI::App& build);
void add_test_shear(CLI::App& test);
void add_test_compress(CLI::App& test);
void add_calibrate_shear(CLI::App& calibrate);
void add_calibrate_compress(CLI::App& calibrate);
// Parameter studies: `study` runs the Python runner packlab.studies (docs/study.md).
void add_study(CLI::App& app);

// Config-file references (io/config.hpp schemas) of the commands that read one, and the
// `config-keys` command printing them all.
std::string vem_config_reference();
std::string ls_config_reference();
std::string scrm_config_reference();
std::string shake_config_reference();
std::string config_reference();
void add_config_keys(CLI::App& app);

}  // namespace packlab::cli
