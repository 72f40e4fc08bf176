// packlab generate lattice --type sc|bcc|fcc --cells NX NY NZ --radius R [--gap G] --out FILE
#include <fmt/format.h>

#include <memory>

#include "packlab/cli/commands.hpp"
#include "packlab/generate/lattice.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::cli {

void add_generate_lattice(CLI::App& generate) {
  struct Options {
    std::string type = "fcc";
    std::vector<int> cells{4, 4, 4};
    double radius = 0.5;
    double gap = 0.0;
    std::string out;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = generate.add_subcommand("lattice", "Cubic lattice (sc, bcc, fcc) in a matching periodic box");
  cmd->add_option("--type", opt->type, "Lattice: sc, bcc or fcc")->capture_default_str();
  cmd->add_option("--cells", opt->cells, "Unit cells along x y z")->expected(3)->capture_default_str();
  cmd->add_option("--radius", opt->radius, "Sphere radius [m]")->capture_default_str();
  cmd->add_option("--gap", opt->gap, "Surface gap between nearest neighbours [m]; 0 = touching")
      ->capture_default_str();
  cmd->add_option("--out", opt->out, "Output file (format by extension: .xyz .vtu .data .csv .txt)")->required();
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt] {
    generate::LatticeParams p;
    p.type = generate::lattice_type_from_name(opt->type);
    p.cells = {opt->cells[0], opt->cells[1], opt->cells[2]};
    p.radius = opt->radius;
    p.gap = opt->gap;
    const Packing packing = generate::make_lattice(p);
    io::WriteOptions w;
    w.comment = fmt::format("packlab generate lattice --type {} --cells {} {} {} --radius {:.17g} --gap {:.17g}",
                            opt->type, p.cells[0], p.cells[1], p.cells[2], p.radius, p.gap);
    io::write_packing(packing, opt->out, w);
    if (!opt->quiet)
      fmt::print("wrote {} particles ({} lattice, volume fraction {:.4f}) to {}\n", packing.size(), opt->type,
                 packing.volume_fraction(), opt->out);
  });
}

}  // namespace packlab::cli
