// The packlab command line: one file per subcommand, each adding itself to the app.
#pragma once

#include <CLI/CLI.hpp>

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
// Issue #4: LS growth, shaking, SCRM, RDF (add_analyze_rdf adds `rdf` to the analyze command).
void add_generate_ls(CLI::App& generate);
void add_generate_scrm(CLI::App& generate);
void add_shake(CLI::App& app);
void add_analyze_rdf(CLI::App& analyze);

}  // namespace packlab::cli
