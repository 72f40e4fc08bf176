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

void add_bond(CLI::App& app) {
  add_option_command(
      app, "bond",
      "Bond every pair closer than a cutoff (contact bonds of touching pairs, or elastic bonds within "
      "1.75 d)",
      io::bond_options,
      {.input = "Input packing (any readable format)",
       .output = "Output bonded model (.vtu: the format that stores bonds)"},
      [](const OptionCommand<io::BondOptions>& c) {
        const io::BondOptions& o = c.settings;
        if (io::format_from_path(c.out) != io::Format::vtu)
          fail_input("--out = " + c.out + ": must end in .vtu (the format that stores bonds)");
        Packing packing = io::read_packing(c.in);
        generate::BondingOptions options;
        options.cutoff_ratio = generate::bonding_cutoff_ratio(o.model, o.eps, o.cutoff_ratio);
        options.threads = o.threads;
        generate::add_bonds(packing, options);
        io::WriteOptions w;
        w.comment = fmt::format("packlab bond {} --model {} cutoff_ratio={:g}", c.in, o.model, options.cutoff_ratio);
        io::write_packing(packing, c.out, w);
        if (!c.quiet) {
          const double per_particle =
              packing.size() > 0 ? 2.0 * static_cast<double>(packing.bonds.size()) / static_cast<double>(packing.size())
                                 : 0.0;
          fmt::print("{} bonds between {} particles ({:.3f} bonded neighbours per particle), wrote {}\n",
                     packing.bonds.size(), packing.size(), per_particle, c.out);
        }
      });
}

}  // namespace packlab::cli
