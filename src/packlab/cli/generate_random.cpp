// packlab generate random --particles N --radius R --phi X [--no-overlap] [--seed S] --out FILE
#include <fmt/format.h>

#include <memory>

#include "packlab/cli/commands.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/random.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::cli {

void add_generate_random(CLI::App& generate) {
  struct Options {
    generate::RandomPackingParams params;
    bool no_overlap = false;
    std::vector<bool> periodic{true, true, true};
    std::uint64_t seed = 1;
    std::string out;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = generate.add_subcommand(
      "random", "Uniform random spheres (overlaps allowed) or random sequential addition (--no-overlap)");
  cmd->add_option("--particles", opt->params.particles, "Number of spheres")->capture_default_str();
  cmd->add_option("--radius", opt->params.radius, "Sphere radius [m]")->capture_default_str();
  cmd->add_option("--phi", opt->params.volume_fraction, "Nominal volume fraction (sum of sphere volumes / box)")
      ->capture_default_str();
  cmd->add_flag("--no-overlap", opt->no_overlap, "Random sequential addition: no two spheres overlap (phi < 0.36)");
  cmd->add_option("--periodic", opt->periodic, "Periodicity along x y z (e.g. 1 1 0)")->expected(3);
  cmd->add_option("--seed", opt->seed, "Random seed")->capture_default_str();
  cmd->add_option("--out", opt->out, "Output file (format by extension)")->required();
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt] {
    auto p = opt->params;
    p.allow_overlap = !opt->no_overlap;
    p.periodic = {opt->periodic[0], opt->periodic[1], opt->periodic[2]};
    Random rng(opt->seed);
    const Packing packing = generate::make_random_packing(p, rng);
    io::WriteOptions w;
    w.comment = fmt::format("packlab generate random --particles {} --radius {:.17g} --phi {:.17g}{} --seed {}",
                            p.particles, p.radius, p.volume_fraction, opt->no_overlap ? " --no-overlap" : "",
                            opt->seed);
    io::write_packing(packing, opt->out, w);
    if (!opt->quiet)
      fmt::print("wrote {} particles (volume fraction {:.4f}) to {}\n", packing.size(), packing.volume_fraction(),
                 opt->out);
  });
}

}  // namespace packlab::cli
