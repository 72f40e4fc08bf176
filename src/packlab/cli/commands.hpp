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
void add_info(CLI::App& app);
void add_convert(CLI::App& app);
void add_relax(CLI::App& app);

}  // namespace packlab::cli
