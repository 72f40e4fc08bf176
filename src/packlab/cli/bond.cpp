// packlab bond IN [--config FILE.toml] --model contact|elastic [--eps 0.01] [--cutoff-ratio 1.75] [--threads T]
//   --out FILE.vtu
// Turns a packing into a bonded model: a bond between every pair closer than the model's
// cutoff, across periodic boundaries (generate/bonding.hpp). The bonds are stored in the file
// (VTU: bonds as line cells with material, state, rest length and periodic image), so every
// later command reads them.
#include <fmt/format.h>

#include <memory>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/core/error.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::cli {

std::string bond_config_reference() {
  io::BondOptions o;
  return io::bond_options(o).markdown();
}

void add_bond(CLI::App& app) {
  struct Options {
    std::string in, out;
    io::BondOptions o;
    std::unique_ptr<OptionFlags> flags;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "bond", "Bond every pair closer than a cutoff (contact bonds of touching pairs, or elastic bonds within 1.75 d)");
  cmd->add_option("in", opt->in, "Input packing (any readable format)")->required();
  cmd->add_option("--out", opt->out, "Output bonded model (.vtu: the format that stores bonds)")->required();
  opt->flags = std::make_unique<OptionFlags>(cmd, io::bond_options(opt->o));
  cmd->add_flag("--quiet", opt->quiet, "No output");
  cmd->callback([opt] {
    opt->flags->load();
    opt->flags->schema().validate();
    if (io::format_from_path(opt->out) != io::Format::vtu)
      fail_input("--out = " + opt->out + ": must end in .vtu (the format that stores bonds)");
    Packing packing = io::read_packing(opt->in);
    generate::BondingOptions options;
    options.cutoff_ratio = generate::bonding_cutoff_ratio(opt->o.model, opt->o.eps, opt->o.cutoff_ratio);
    options.threads = opt->o.threads;
    generate::add_bonds(packing, options);
    io::WriteOptions w;
    w.comment = fmt::format("packlab bond {} --model {} cutoff_ratio={:g}", opt->in, opt->o.model, options.cutoff_ratio);
    io::write_packing(packing, opt->out, w);
    if (!opt->quiet) {
      const double per_particle =
          packing.size() > 0 ? 2.0 * static_cast<double>(packing.bonds.size()) / static_cast<double>(packing.size())
                             : 0.0;
      fmt::print("{} bonds between {} particles ({:.3f} bonded neighbours per particle), wrote {}\n", packing.bonds.size(),
                 packing.size(), per_particle, opt->out);
    }
  });
}

}  // namespace packlab::cli
