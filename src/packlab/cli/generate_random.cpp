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

void add_generate_random(CLI::App& generate) {
  add_option_command(
      generate, "random", "Uniform random spheres (overlaps allowed) or random sequential addition (--no-overlap)",
      io::random_options, {.output = "Output file (format by extension)"},
      [](const OptionCommand<io::RandomOptions>& c) {
        const generate::RandomPackingParams p = c.settings.params();
        Random rng(c.settings.seed);
        const Packing packing = generate::make_random_packing(p, rng);
        io::WriteOptions w;
        w.comment = fmt::format("packlab generate random --particles {} --radius {:.17g} --phi {:.17g}{} --seed {}",
                                p.particles, p.radius, p.volume_fraction, c.settings.no_overlap ? " --no-overlap" : "",
                                c.settings.seed);
        io::write_packing(packing, c.out, w);
        if (!c.quiet)
          fmt::print("wrote {} particles (volume fraction {:.4f}) to {}\n", packing.size(), packing.volume_fraction(),
                     c.out);
      });
}

}  // namespace packlab::cli
