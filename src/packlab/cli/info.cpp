// packlab info FILE [--json] [--contact-eps 0.01]
#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "packlab/analyze/coordination.hpp"
#include "packlab/cli/commands.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::cli {

void add_info(CLI::App& app) {
  struct Options {
    std::string file;
    bool json = false;
    double contact_eps = 0.01;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("info", "Particles, box, volume fraction and mean coordination of a packing");
  cmd->add_option("file", opt->file, "Packing file")->required();
  cmd->add_flag("--json", opt->json, "Print one JSON object");
  cmd->add_option("--contact-eps", opt->contact_eps, "Contact tolerance: in contact when distance < (1+eps)(r_i+r_j)")
      ->capture_default_str();
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt] {
    const Packing packing = io::read_packing(opt->file);
    analyze::Coordination cn(opt->contact_eps);
    cn.compute(packing);
    const Box& b = packing.box;
    if (opt->json) {
      nlohmann::json j;
      j["file"] = opt->file;
      j["particles"] = packing.size();
      j["box"] = {b.length.x, b.length.y, b.length.z};
      j["origin"] = {b.lo.x, b.lo.y, b.lo.z};
      j["periodic"] = {b.periodic[0], b.periodic[1], b.periodic[2]};
      j["volume_fraction"] = packing.volume_fraction();
      j["mean_coordination"] = cn.mean();
      j["contact_eps"] = opt->contact_eps;
      j["bonds"] = packing.bonds.size();
      fmt::print("{}\n", j.dump());
      return;
    }
    double r_min = packing.radius.empty() ? 0.0 : packing.radius[0], r_max = r_min;
    for (double r : packing.radius) {
      r_min = std::min(r_min, r);
      r_max = std::max(r_max, r);
    }
    fmt::print("file               {}\n", opt->file);
    fmt::print("particles          {}\n", packing.size());
    fmt::print("box                {:.9g} x {:.9g} x {:.9g} m (origin {:.9g} {:.9g} {:.9g})\n", b.length.x, b.length.y,
               b.length.z, b.lo.x, b.lo.y, b.lo.z);
    fmt::print("periodic           {} {} {}\n", b.periodic[0], b.periodic[1], b.periodic[2]);
    fmt::print("radius             {:.6g} .. {:.6g} m\n", r_min, r_max);
    fmt::print("volume fraction    {:.6f}\n", packing.volume_fraction());
    fmt::print("mean coordination  {:.6f} (contact eps {:g})\n", cn.mean(), opt->contact_eps);
    if (!packing.bonds.empty()) fmt::print("bonds              {}\n", packing.bonds.size());
  });
}

}  // namespace packlab::cli
