// packlab generate lattice [--config FILE.toml] --type sc|bcc|fcc --cells NX NY NZ --radius R [--gap G] --out FILE
#include <fmt/format.h>

#include <memory>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/generate/lattice.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::cli {

std::string lattice_config_reference() {
  io::LatticeOptions o;
  return io::lattice_options(o).markdown();
}

void add_generate_lattice(CLI::App& generate) {
  struct Options {
    io::LatticeOptions o;
    std::unique_ptr<OptionFlags> flags;
    std::string out;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = generate.add_subcommand("lattice", "Cubic lattice (sc, bcc, fcc) in a matching periodic box");
  opt->flags = std::make_unique<OptionFlags>(cmd, io::lattice_options(opt->o));
  cmd->add_option("--out", opt->out, "Output file (format by extension: .xyz .vtu .data .csv .txt)")->required();
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt] {
    opt->flags->load();
    const generate::LatticeParams p = opt->o.params();
    const Packing packing = generate::make_lattice(p);
    opt->flags->schema().validate();
    io::WriteOptions w;
    w.comment = fmt::format("packlab generate lattice --type {} --cells {} {} {} --radius {:.17g} --gap {:.17g}",
                            opt->o.type, p.cells[0], p.cells[1], p.cells[2], p.radius, p.gap);
    io::write_packing(packing, opt->out, w);
    if (!opt->quiet)
      fmt::print("wrote {} particles ({} lattice, volume fraction {:.4f}) to {}\n", packing.size(), opt->o.type,
                 packing.volume_fraction(), opt->out);
  });
}

}  // namespace packlab::cli
