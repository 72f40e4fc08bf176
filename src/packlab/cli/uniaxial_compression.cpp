// packlab test compress IN [--config FILE.toml] --out DIR [every option of io::compression_test_options as a
//   flag: --bond-youngs-modulus E --bond-poisson-ratio NU --bond-strength S --strain-rate R --max-strain X
//   --sides periodic|open --substrate-layers N ...]
// Uniaxial compression of a bonded model (mechanics/uniaxial_compression.hpp, bpm-inverse-opals):
// any model with bonds (an opal from `packlab build opal`, or `packlab bond IN --model elastic`
// over any packing). Writes DIR/report.json ({"youngs_modulus", "strength", "broken_bonds", ...}
// in SI), curve.csv, bond_strain.csv, particle_stress.csv, broken_bonds.csv/.vtu, model.vtu and
// the plots. Flags override the config file.
// packlab test compress --resume DIR [--threads T] [--adapt-threads=false]
// The dynamic solver writes DIR/checkpoint.bin every --checkpoint-seconds and at the end
// (cli/checkpoint.hpp), the static solver (--solver static) at its fresh factorizations every
// --checkpoint-breaks breaks once --checkpoint-seconds have passed; --resume DIR goes on from it
// and writes the same files as an uninterrupted run.
#include "packlab/mechanics/uniaxial_compression.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <sstream>

#include "packlab/cli/checkpoint.hpp"
#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/cli/uniaxial_compression_output.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/mechanics_report.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/report.hpp"
#include "packlab/mechanics/opal_materials.hpp"

namespace packlab::cli {

void add_test_compress(CLI::App& test) {
  auto no_vtu = std::make_shared<bool>(false);
  CLI::App* cmd = add_option_command(
      test, "compress", "Uniaxial compression of a bonded model by a plate moving down at a set strain rate",
      io::compression_test_options,
      {.input = "Bonded model (.vtu from `packlab build opal` or `packlab bond`)",
       .output = "Output folder",
       .plots = true,
       .resumable = true},
      [no_vtu](OptionCommand<mechanics::UniaxialCompressionSetup>& c) {
        const Packing model = io::read_packing(c.in);
        mechanics::UniaxialCompressionSetup s = c.settings;
        s.finish(model);
        s.options.validate();
        const std::filesystem::path dir = c.out;
        const io::OutputFolder folder(dir);  // removed again when the model is refused
        Progress progress("compress", 1000, !c.quiet);
        const double max_strain = s.options.max_strain;
        s.options.on_point = [&](const mechanics::UniaxialCompressionPoint& p) {
          progress.update(
              static_cast<long>(1000.0 * p.strain / max_strain),
              fmt::format("strain {:.4f}, stress {:.4g} MPa, broken {}", p.strain, p.stress * 1e-6, p.broken_bonds));
        };
        CheckpointWriter checkpoint(dir, c.flags->schema(), c.in, c.settings.checkpoint_seconds);
        s.options.checkpoint = [&](const std::function<void(std::ostream&)>& state, bool end) {
          end ? checkpoint.write(state) : checkpoint.write_if_due(state);
        };
        if (c.resumed) s.options.resume = &c.resumed->state;
        const mechanics::UniaxialCompressionResult r = mechanics::run_uniaxial_compression(model, s.options);
        progress.finish();
        nlohmann::json report = io::report_header("test compress");
        report["input"] = c.in;
        report["parameters"] = c.flags->schema().json();
        report.update(io::uniaxial_compression_summary(r, s.options));
        write_uniaxial_compression_outputs(r, s.options, dir, !c.no_plots, !*no_vtu);
        io::write_report(dir / "report.json", report);
        if (!c.quiet) {
          fmt::print("{} particles ({} fixed), {} bonds ({} left out), H0 = {:.4g} m, A = {:.4g} m^2\n", r.particles,
                     r.fixed_particles, r.bonds, r.dropped_bonds, r.height, r.area);
          if (r.solver == "static") {
            fmt::print(
                "static solver ({}): {} solves, {} factorizations, {} downdates, {} checks, {} rollbacks, {:.1f} MB; "
                "{}\n",
                s.options.solver_backend, r.solves, r.factorizations, r.downdates, r.checks, r.rollbacks,
                static_cast<double>(r.solver_bytes) * 1e-6, r.stop_reason);
            fmt::print(
                "Young's modulus {:.5g} GPa (linear solve), Poisson's ratio {}, strength {:.5g} MPa at strain "
                "{:.4g} (sequential linear analysis), {} broken bonds\n",
                r.youngs_modulus * 1e-9,
                std::isfinite(r.poisson_ratio) ? fmt::format("{:.4g}", r.poisson_ratio) : "- (periodic sides)",
                r.strength * 1e-6, r.strain_at_peak, r.broken_bonds);
            fmt::print("wrote {} in {:.1f} s\n", (dir / "report.json").string(), r.seconds);
          } else {
            fmt::print("strain rate {:.4g} 1/s, time step {:.4g} s, {} steps; {}\n", s.options.strain_rate, r.time_step,
                       r.steps, r.stop_reason);
            if (s.options.elastic_speedup > 1.0)
              fmt::print(
                  "adaptive rate: {:.3g}x until strain {} (after the last point before the first break), {} fast "
                  "steps discarded\n",
                  r.effective_speedup,
                  std::isfinite(r.rate_switch_strain) ? fmt::format("{:.4g}", r.rate_switch_strain)
                                                      : std::string("- (no break)"),
                  r.rolled_back_steps);
            fmt::print(
                "Young's modulus {:.5g} GPa (fit over strain {:.4g}..{:.4g}), strength {:.5g} MPa at strain {:.4g}, "
                "{} broken bonds\n",
                r.youngs_modulus * 1e-9, r.modulus.strain_begin, r.modulus.strain_end, r.strength * 1e-6,
                r.strain_at_peak, r.broken_bonds);
            fmt::print("max kinetic / strain energy before the peak {:.3g}; wrote {} in {:.1f} s\n",
                       r.max_kinetic_ratio, (dir / "report.json").string(), r.seconds);
          }
        }
      });
  cmd->add_flag("--no-vtu", *no_vtu, "Do not write the final model (model.vtu)");
  cmd->footer(
      "Checkpoints (--checkpoint-seconds, --resume): the dynamic solver writes one every --checkpoint-seconds and "
      "at the end; --solver static at the first of its fresh factorizations (every --checkpoint-breaks breaks) "
      "after --checkpoint-seconds. A resumed run writes the files of an uninterrupted one.");
}

}  // namespace packlab::cli
