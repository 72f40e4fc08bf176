// packlab bond IN --model contact|elastic [--eps 0.01] [--cutoff-ratio 1.75] --out FILE.vtu
// Turns a packing into a bonded model: a bond between every pair closer than the model's
// cutoff, across periodic boundaries (generate/bonding.hpp). The bonds are stored in the file
// (VTU: bonds as line cells with material, state, rest length and periodic image), so every
// later command reads them.
#include <fmt/format.h>

#include <memory>

#include "packlab/cli/commands.hpp"
#include "packlab/core/error.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::cli {

void add_bond(CLI::App& app) {
  struct Options {
    std::string in, out;
    std::string model = "contact";
    double eps = 0.01;
    double cutoff_ratio = 1.75;
    int threads = 1;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "bond", "Bond every pair closer than a cutoff (contact bonds of touching pairs, or elastic bonds within 1.75 d)");
  cmd->add_option("in", opt->in, "Input packing (any readable format)")->required();
  cmd->add_option("--out", opt->out, "Output bonded model (.vtu: the format that stores bonds)")->required();
  cmd->add_option("--model", opt->model,
                  "contact: pairs with d < (1 + eps)(r_i + r_j) (PFC contact bonds, doh-elastic-properties "
                  "§2.1); elastic: pairs with d < cutoff-ratio (r_i + r_j) (elastic beam bonds, bpm-inverse-opals "
                  "§2.1)")
      ->capture_default_str();
  cmd->add_option("--eps", opt->eps, "Contact tolerance of the contact model, in [0, 1)")->capture_default_str();
  cmd->add_option("--cutoff-ratio", opt->cutoff_ratio,
                  "Elastic model: bond pairs closer than this times r_i + r_j (1.75 d for equal spheres), in [1, 2)")
      ->capture_default_str();
  cmd->add_option("--threads", opt->threads, "Threads of the pair search")->capture_default_str();
  cmd->add_flag("--quiet", opt->quiet, "No output");
  cmd->callback([opt] {
    if (io::format_from_path(opt->out) != io::Format::vtu)
      fail_input("--out = " + opt->out + ": must end in .vtu (the format that stores bonds)");
    Packing packing = io::read_packing(opt->in);
    generate::BondingOptions options;
    options.cutoff_ratio = generate::bonding_cutoff_ratio(opt->model, opt->eps, opt->cutoff_ratio);
    options.threads = opt->threads;
    generate::add_bonds(packing, options);
    io::WriteOptions w;
    w.comment = fmt::format("packlab bond {} --model {} cutoff_ratio={:g}", opt->in, opt->model, options.cutoff_ratio);
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
