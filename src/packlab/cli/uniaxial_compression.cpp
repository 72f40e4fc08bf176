// packlab test compress IN [--config FILE.toml] --out DIR [--bond-youngs-modulus E] [--bond-poisson NU]
//   [--bond-strength S] [--strain-rate R] [--max-strain X] [--sides periodic|open] [--substrate-layers N] ...
// Uniaxial compression of a bonded model (mechanics/uniaxial_compression.hpp, bpm-inverse-opals):
// any model with bonds (an opal from `packlab build opal`, or `packlab bond IN --model elastic`
// over any packing). Writes DIR/report.json ({"youngs_modulus", "strength", "broken_bonds", ...}
// in SI), curve.csv, bond_strain.csv, particle_stress.csv, broken_bonds.csv/.vtu, model.vtu and
// the plots. Flags override the config file.
#include <fmt/format.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <sstream>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/uniaxial_compression_output.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/io/config.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/report.hpp"
#include "packlab/mechanics/opal_materials.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"

namespace packlab::cli {

// The flags and config keys of a compression run, shared with calibrate_compress.cpp (which
// sees this type only by name).
using CompressSettings = mechanics::UniaxialCompressionSetup;
struct CompressFlags {
  CompressSettings flags;  // what the flags parsed into
  std::vector<std::pair<std::string, std::function<void(const CompressSettings&, CompressSettings&)>>> copy;
  std::vector<std::function<void(io::ConfigSchema&, CompressSettings&)>> keys;
};

namespace {

template <class T>
void bind_setting(CLI::App* cmd, CompressFlags& f, const std::string& flag, const std::string& key, T& (*get)(CompressSettings&),
          const std::string& description) {
  cmd->add_option(flag, get(f.flags), description)->capture_default_str();
  f.copy.emplace_back(flag, [get](const CompressSettings& from, CompressSettings& to) {
    get(to) = get(const_cast<CompressSettings&>(from));
  });
  f.keys.push_back([get, key, description](io::ConfigSchema& schema, CompressSettings& s) {
    if constexpr (std::is_same_v<T, double>)
      schema.number(key, get(s), description);
    else if constexpr (std::is_same_v<T, bool>)
      schema.boolean(key, get(s), description);
    else if constexpr (std::is_same_v<T, std::string>)
      schema.text(key, get(s), description);
    else
      schema.integer(key, get(s), description);
  });
}

}  // namespace

std::shared_ptr<CompressFlags> add_compression_flags(CLI::App* cmd) {
  auto flags = std::make_shared<CompressFlags>();
  CompressFlags& f = *flags;
#define PL_GET(expr) +[](CompressSettings& s) -> decltype(auto) { return (expr); }
  bind_setting<double>(cmd, f, "--bond-youngs-modulus", "silica.youngs_modulus", PL_GET(s.materials.silica_youngs_modulus),
               "Silica bond and particle Young's modulus E_b [Pa] (bond material 0; also every bond of a one-material model)");
  bind_setting<double>(cmd, f, "--bond-poisson", "silica.poisson_ratio", PL_GET(s.materials.silica_poisson_ratio),
               "Silica bond Poisson ratio nu_b [-]");
  bind_setting<double>(cmd, f, "--bond-strength", "silica.strength", PL_GET(s.materials.silica_strength),
               "Silica bond strength sigma_max = tau_max [Pa] (eq. 16-17)");
  bind_setting<double>(cmd, f, "--density", "silica.density", PL_GET(s.materials.silica_density), "Silica particle density [kg/m^3]");
  bind_setting<double>(cmd, f, "--titania-youngs-modulus", "titania.youngs_modulus", PL_GET(s.materials.titania_youngs_modulus),
               "Titania (coating) bond Young's modulus [Pa] (bond material 1)");
  bind_setting<double>(cmd, f, "--titania-poisson", "titania.poisson_ratio", PL_GET(s.materials.titania_poisson_ratio),
               "Titania bond Poisson ratio [-]");
  bind_setting<double>(cmd, f, "--titania-strength", "titania.strength", PL_GET(s.materials.titania_strength),
               "Titania bond strength [Pa]");
  bind_setting<double>(cmd, f, "--titania-density", "titania.density", PL_GET(s.materials.titania_density),
               "Titania particle density [kg/m^3]");
  bind_setting<double>(cmd, f, "--restitution", "contact.restitution", PL_GET(s.materials.restitution),
               "Restitution coefficient of unbonded contacts and the plate, in (0, 1]");
  bind_setting<double>(cmd, f, "--friction", "contact.friction", PL_GET(s.materials.friction), "Sliding friction mu_sl [-]");
  bind_setting<double>(cmd, f, "--rolling-friction", "contact.rolling_friction", PL_GET(s.materials.rolling_friction),
               "Rolling friction mu_r [-]");
  bind_setting<double>(cmd, f, "--damping", "contact.damping", PL_GET(s.materials.damping),
               "Local (Cundall) damping alpha in [0, 1) for the quasi-static run");
  bind_setting<double>(cmd, f, "--bond-radius-ratio", "bond.radius_ratio", PL_GET(s.materials.bond_radius_ratio),
               "Bond radius / smaller particle radius, in (0, 1]");
  bind_setting<double>(cmd, f, "--relaxation-time", "bond.relaxation_time", PL_GET(s.materials.relaxation_time),
               "Time a failed bond stays while its stiffness decays linearly to zero [s]");
  bind_setting<bool>(cmd, f, "--compressive-breakage", "bond.compressive_breakage",
                     PL_GET(s.materials.compressive_breakage),
                     "Apply the normal-stress criterion (eq. 16) to compressed bonds too (default: stretched only, as MUSEN)");
  bind_setting<double>(cmd, f, "--strain-rate", "test.strain_rate", PL_GET(s.strain_rate),
               "Plate speed / sample height [1/s]; 0 = automatic: --quasi-static strain per elastic-wave transit");
  bind_setting<double>(cmd, f, "--quasi-static", "test.quasi_static", PL_GET(s.quasi_static),
               "Automatic rate: strain per time sqrt(rho/E_b) H0 (smaller = slower, closer to quasi-static)");
  bind_setting<double>(cmd, f, "--max-strain", "test.max_strain", PL_GET(s.options.max_strain), "Largest strain [-]");
  bind_setting<double>(cmd, f, "--stop-drop", "test.stop_drop", PL_GET(s.options.stop_drop),
               "Stop past the peak once the stress is below this fraction of it (0 = run to --max-strain)");
  bind_setting<std::string>(cmd, f, "--sides", "test.sides", PL_GET(s.options.sides),
                    "periodic: keep the model's periodic x, y; open: free-standing pillar");
  bind_setting<std::string>(cmd, f, "--plate", "test.plate", PL_GET(s.options.plate),
                    "glued: the top --plate-layers move with the plate (no contact toe); contact: a Hertz-Mindlin "
                    "plate touching the top (the paper's; rough tops give a toe of about r / H0)");
  bind_setting<double>(cmd, f, "--plate-layers", "test.plate_layers", PL_GET(s.options.plate_layers),
               "Glued plate: top layers moving with it (mean diameters)");
  bind_setting<double>(cmd, f, "--substrate-layers", "test.substrate_layers", PL_GET(s.options.substrate_layers),
               "Bottom layers fixed when the model has no fixed particles (mean diameters)");
  bind_setting<double>(cmd, f, "--time-step", "test.time_step", PL_GET(s.options.time_step),
               "Time step [s]; 0 = safety x min sqrt(m/k)");
  bind_setting<double>(cmd, f, "--time-step-safety", "test.time_step_safety", PL_GET(s.options.time_step_safety),
               "Safety factor of the automatic time step");
  bind_setting<long>(cmd, f, "--samples", "test.samples", PL_GET(s.options.samples), "Curve points over --max-strain");
  bind_setting<double>(cmd, f, "--modulus-lower", "analysis.modulus_lower", PL_GET(s.options.modulus_lower),
               "Young's modulus fit: ignore points below this fraction of the peak stress");
  bind_setting<double>(cmd, f, "--modulus-window", "analysis.modulus_window", PL_GET(s.options.modulus_window),
               "Young's modulus fit: window width as a fraction of the peak stress");
  bind_setting<int>(cmd, f, "--threads", "threads", PL_GET(s.options.threads), "OpenMP threads (0 = all cores)");
#undef PL_GET
  cmd->add_option("--snapshot-strains", f.flags.snapshot_strains,
                  "Strains at which bond strains and particle stresses are recorded (Fig. 7, Table 2)")
      ->delimiter(',');
  f.copy.emplace_back("--snapshot-strains",
                      [](const CompressSettings& from, CompressSettings& to) { to.snapshot_strains = from.snapshot_strains; });
  return flags;
}

// Settings of this run: defaults, then the config file, then the flags given.
CompressSettings resolve_compression_settings(CLI::App* cmd, const CompressFlags& f, const std::string& config,
                                              const Packing& model) {
  CompressSettings s;
  if (!config.empty()) {
    io::ConfigSchema schema(cmd->get_parent() ? cmd->get_parent()->get_name() + " " + cmd->get_name() : cmd->get_name());
    for (const auto& k : f.keys) k(schema, s);
    schema.read_file(config);
  }
  for (const auto& [flag, copy] : f.copy)
    if (cmd->count(flag) > 0) copy(f.flags, s);
  s.finish(model);
  return s;
}

std::string compress_config_reference() {
  CLI::App app;
  const auto flags = add_compression_flags(app.add_subcommand("compress"));
  CompressSettings s;
  io::ConfigSchema schema("test compress",
                          "Uniaxial compression of a bonded model (docs/opal.md); flags override the file; "
                          "`calibrate compress` reads the same keys.");
  for (const auto& k : flags->keys) k(schema, s);
  return schema.markdown();
}

void add_test_compress(CLI::App& test) {
  struct Options {
    std::string in, out, config;
    bool quiet = false, no_plots = false, no_vtu = false;
    std::shared_ptr<CompressFlags> flags;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = test.add_subcommand("compress",
                                  "Uniaxial compression of a bonded model by a plate moving down at a set strain rate");
  cmd->add_option("in", opt->in, "Bonded model (.vtu from `packlab build opal` or `packlab bond`)")->required();
  cmd->add_option("--out", opt->out, "Output folder")->required();
  cmd->add_option("--config", opt->config, "TOML file with any of the settings; flags override it");
  opt->flags = add_compression_flags(cmd);
  cmd->add_flag("--no-plots", opt->no_plots, "Do not make PNG plots");
  cmd->add_flag("--no-vtu", opt->no_vtu, "Do not write the final model (model.vtu)");
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt, cmd] {
    const Packing model = io::read_packing(opt->in);
    CompressSettings s = resolve_compression_settings(cmd, *opt->flags, opt->config, model);
    Progress progress("compress", 1000, !opt->quiet);
    const double max_strain = s.options.max_strain;
    s.options.on_point = [&](const mechanics::UniaxialCompressionPoint& p) {
      progress.update(static_cast<long>(1000.0 * p.strain / max_strain),
                      fmt::format("strain {:.4f}, stress {:.4g} MPa, broken {}", p.strain, p.stress * 1e-6, p.broken_bonds));
    };
    const mechanics::UniaxialCompressionResult r = mechanics::run_uniaxial_compression(model, s.options);
    progress.finish();
    nlohmann::json report = io::report_header("test compress");
    report["input"] = opt->in;
    report["materials"] = {{"silica", {{"youngs_modulus", s.materials.silica_youngs_modulus},
                                       {"poisson_ratio", s.materials.silica_poisson_ratio},
                                       {"strength", s.materials.silica_strength},
                                       {"density", s.materials.silica_density}}},
                           {"titania", {{"youngs_modulus", s.materials.titania_youngs_modulus},
                                        {"poisson_ratio", s.materials.titania_poisson_ratio},
                                        {"strength", s.materials.titania_strength},
                                        {"density", s.materials.titania_density}}},
                           {"restitution", s.materials.restitution},
                           {"friction", s.materials.friction},
                           {"rolling_friction", s.materials.rolling_friction},
                           {"damping", s.materials.damping},
                           {"bond_radius_ratio", s.materials.bond_radius_ratio},
                           {"relaxation_time", s.materials.relaxation_time}};
    report.update(uniaxial_compression_report(r, s.options));
    const std::filesystem::path dir = opt->out;
    write_uniaxial_compression_outputs(r, s.options, dir, !opt->no_plots, !opt->no_vtu);
    io::write_report(dir / "report.json", report);
    if (!opt->quiet) {
      fmt::print("{} particles ({} fixed), {} bonds ({} left out), H0 = {:.4g} m, A = {:.4g} m^2\n", r.particles,
                 r.fixed_particles, r.bonds, r.dropped_bonds, r.height, r.area);
      fmt::print("strain rate {:.4g} 1/s, time step {:.4g} s, {} steps; {}\n", s.options.strain_rate, r.time_step, r.steps,
                 r.stop_reason);
      fmt::print("Young's modulus {:.5g} GPa (fit over strain {:.4g}..{:.4g}), strength {:.5g} MPa at strain {:.4g}, "
                 "{} broken bonds\n",
                 r.youngs_modulus * 1e-9, r.modulus.strain_begin, r.modulus.strain_end, r.strength * 1e-6, r.strain_at_peak,
                 r.broken_bonds);
      fmt::print("max kinetic / strain energy before the peak {:.3g}; wrote {} in {:.1f} s\n", r.max_kinetic_ratio,
                 (dir / "report.json").string(), r.seconds);
    }
  });
}

}  // namespace packlab::cli
