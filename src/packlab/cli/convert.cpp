// packlab convert IN OUT: any readable format to any writable one (by extension).
#include <fmt/format.h>

#include <memory>

#include "packlab/cli/commands.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::cli {

void add_convert(CLI::App& app) {
  struct Options {
    std::string in, out;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("convert", "Convert a packing between formats (chosen by extension)");
  cmd->add_option("in", opt->in, "Input file")->required();
  cmd->add_option("out", opt->out, "Output file")->required();
  cmd->add_flag("--quiet", opt->quiet, "No output");
  cmd->callback([opt] {
    const Packing packing = io::read_packing(opt->in);
    io::WriteOptions w;
    w.comment = fmt::format("packlab convert from {}", opt->in);
    io::write_packing(packing, opt->out, w);
    if (!opt->quiet) fmt::print("wrote {} particles to {}\n", packing.size(), opt->out);
  });
}

}  // namespace packlab::cli
