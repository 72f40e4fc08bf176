// packlab generate lattice [--config FILE.toml] --type sc|bcc|fcc --cells NX NY NZ --radius R [--gap G] --out FILE
#include <fmt/format.h>

#include <memory>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/generate/lattice.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::cli {

void add_generate_lattice(CLI::App& generate) {
  add_option_command(generate, "lattice", "Cubic lattice (sc, bcc, fcc) in a matching periodic box",
                     io::lattice_options, {.output = "Output file (format by extension: .xyz .vtu .data .csv .txt)"},
                     [](const OptionCommand<io::LatticeOptions>& c) {
                       const generate::LatticeParams p = c.settings.params();
                       const Packing packing = generate::make_lattice(p);
                       io::WriteOptions w;
                       w.comment = fmt::format(
                           "packlab generate lattice --type {} --cells {} {} {} --radius {:.17g} --gap {:.17g}",
                           c.settings.type, p.cells[0], p.cells[1], p.cells[2], p.radius, p.gap);
                       io::write_packing(packing, c.out, w);
                       if (!c.quiet)
                         fmt::print("wrote {} particles ({} lattice, volume fraction {:.4f}) to {}\n", packing.size(),
                                    c.settings.type, packing.volume_fraction(), c.out);
                     });
}

}  // namespace packlab::cli
