// packlab generate random --particles N --radius R --phi X [--no-overlap] [--seed S] --out FILE
#include <fmt/format.h>

#include <memory>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/random.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::cli {

std::string random_config_reference() {
  io::RandomOptions o;
  return io::random_options(o).markdown();
}

void add_generate_random(CLI::App& generate) {
  struct Options {
    io::RandomOptions o;
    std::unique_ptr<OptionFlags> flags;
    std::string out;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = generate.add_subcommand(
      "random", "Uniform random spheres (overlaps allowed) or random sequential addition (--no-overlap)");
  opt->flags = std::make_unique<OptionFlags>(cmd, io::random_options(opt->o));
  cmd->add_option("--out", opt->out, "Output file (format by extension)")->required();
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt] {
    opt->flags->load();
    const generate::RandomPackingParams p = opt->o.params();
    Random rng(opt->o.seed);
    const Packing packing = generate::make_random_packing(p, rng);
    opt->flags->schema().validate();
    io::WriteOptions w;
    w.comment = fmt::format("packlab generate random --particles {} --radius {:.17g} --phi {:.17g}{} --seed {}",
                            p.particles, p.radius, p.volume_fraction, opt->o.no_overlap ? " --no-overlap" : "",
                            opt->o.seed);
    io::write_packing(packing, opt->out, w);
    if (!opt->quiet)
      fmt::print("wrote {} particles (volume fraction {:.4f}) to {}\n", packing.size(), packing.volume_fraction(),
                 opt->out);
  });
}

}  // namespace packlab::cli
