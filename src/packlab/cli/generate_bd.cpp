// packlab generate bd [--config FILE.toml] --particles N [--phi 0.4] [--surface-potential 15e-3]
//   [--hamaker-constant A] [--debye-length L | --ionic-strength I] [--radius R] [--temperature T]
//   [--viscosity ETA] [--duration T] [--until-stable] [--msd] [--seed S] [--checkpoint-seconds S] --out DIR
// packlab generate bd --resume DIR [--threads T]
// Brownian-dynamics coagulation with the DLVO potential (generate/brownian_dynamics.hpp,
// docs/bd.md, doh-elastic-properties §2.2). Writes DIR/packing.xyz, packing.vtu (with the
// bonds), report.json, potential.csv + potential.png (the pair potential in k_B T against the
// separation), bd_log.csv (bonds and clusters against time), with --msd msd.csv, and
// checkpoint.bin (every --checkpoint-seconds and at the end; --resume DIR goes on from it).
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>

#include "packlab/analyze/coordination.hpp"
#include "packlab/cli/checkpoint.hpp"
#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/generate/brownian_dynamics.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

namespace {

// U(h)/kT and F(h) of the law as simulated (h_min, cut-off, energy shift) and unshifted.
std::string potential_table(const generate::BdParams& p) {
  dem::Dlvo::Params law = p.dlvo();
  const double kT = p.kT(), a = p.radius;
  std::ostringstream out;
  out << "separation_m,separation_over_radius,energy_kT,van_der_waals_kT,double_layer_kT,force_N\n";
  const int n = 400;
  const double lo = law.min_separation, hi = law.cutoff;
  for (int k = 0; k < n; ++k) {
    const double h = lo * std::pow(hi / lo, static_cast<double>(k) / (n - 1));
    const auto u = dem::Dlvo::potential(law, a, a, h);
    out << fmt::format("{:.6e},{:.6e},{:.8g},{:.8g},{:.8g},{:.6e}\n", h, h / a, u.energy / kT,
                       dem::Dlvo::van_der_waals(law, a, a, h).energy / kT,
                       dem::Dlvo::double_layer(law, a, a, h).energy / kT, u.force);
  }
  return out.str();
}

}  // namespace

void add_generate_bd(CLI::App& generate) {
  add_option_command(
      generate, "bd",
      "Brownian-dynamics coagulation of colloids with the DLVO potential (doh-elastic-properties §2.2, docs/bd.md)",
      io::bd_options, {.output = "Output folder", .plots = true, .resumable = true},
      [](OptionCommand<io::BdOptions>& c) {
        const auto t0 = std::chrono::steady_clock::now();
        const io::BdOptions& o = c.settings;
        o.bd.validate();
        io::ensure_directory(c.out);
        std::optional<generate::BdRun> bd;
        if (c.resumed)
          bd.emplace(generate::BdRun::load_state(c.resumed->state, o.bd.threads));
        else
          bd.emplace(o.bd, Random(o.seed));
        const generate::BdParams& p = bd->params();
        Progress progress("generate bd", bd->total_steps(), !c.quiet);
        const auto on_progress = [&](const generate::BdStatus& s) {
          progress.update(s.step, fmt::format("t = {:.4g} a^2/D0, {} bonds, largest cluster {}", s.reduced_time,
                                              s.bonds, s.largest_cluster));
        };
        const long n = p.particles;
        const long chunk = std::max(1L, 200'000L / n);  // ~0.1 s of steps between checkpoint chances
        CheckpointWriter checkpoint(c.out, c.flags->schema(), c.in, o.checkpoint_seconds);
        const auto save = [&](std::ostream& out) { bd->save_state(out); };
        while (!bd->run(chunk, on_progress)) checkpoint.write_if_due(save);
        checkpoint.write(save);
        progress.finish();
        const generate::BdResult r = bd->result();
        const Packing& packing = r.packing;
        const std::filesystem::path dir(c.out);
        io::WriteOptions w;
        w.comment =
            fmt::format("packlab {} generate bd N={} phi={:g} surface_potential={:g} V t={:.6g} a^2/D0 seed={}",
                        io::version(), n, p.volume_fraction, p.surface_potential, r.status.reduced_time, o.seed);
        io::write_packing(packing, dir / "packing.xyz", w);
        io::write_packing(packing, dir / "packing.vtu", w);
        // Tables.
        io::write_text_atomically(dir / "potential.csv", potential_table(p));
        std::ostringstream log;
        log << "step,time_s,reduced_time,bonds,mean_coordination,clusters,largest_cluster,msd_m2\n";
        for (const auto& s : r.log)
          log << fmt::format("{},{:.8e},{:.8g},{},{:.6g},{},{},{:.8e}\n", s.step, s.time, s.reduced_time, s.bonds,
                             2.0 * static_cast<double>(s.bonds) / static_cast<double>(n), s.clusters, s.largest_cluster,
                             s.msd);
        io::write_text_atomically(dir / "bd_log.csv", log.str());
        const double d0 = p.diffusion_coefficient();
        double fitted_d = 0.0;
        if (o.msd) {
          std::ostringstream msd;
          msd << "time_s,reduced_time,msd_m2,msd_over_6_d0_t\n";
          for (const auto& s : r.log)
            msd << fmt::format("{:.8e},{:.8g},{:.8e},{:.8g}\n", s.time, s.reduced_time, s.msd,
                               s.time > 0 ? s.msd / (6.0 * d0 * s.time) : 1.0);
          io::write_text_atomically(dir / "msd.csv", msd.str());
        }
        // Least-squares slope of MSD = 6 D t through the origin over the log.
        double st = 0, tt = 0;
        for (const auto& s : r.log) {
          st += s.msd * s.time;
          tt += s.time * s.time;
        }
        if (tt > 0) fitted_d = st / tt / 6.0;
        io::PlotOptions po;
        po.enabled = !c.no_plots;
        io::make_plot("bd_potential", {(dir / "potential.csv").string()}, dir / "potential.png", po);
        // Report.
        const generate::DlvoProfile profile = generate::dlvo_profile(p.dlvo(), p.radius, p.kT());
        analyze::Coordination cn(0.01);
        cn.compute(packing);
        nlohmann::json report = io::report_header("generate bd");
        report["parameters"] = {{"particles", n},
                                {"volume_fraction", p.volume_fraction},
                                {"radius_m", p.radius},
                                {"box_edge_m", p.box_edge()},
                                {"hamaker_constant_J", p.hamaker_constant},
                                {"surface_potential_V", p.surface_potential},
                                {"debye_length_m", p.screening_length()},
                                {"ionic_strength_mol_per_m3", p.ionic_strength},
                                {"relative_permittivity", p.relative_permittivity},
                                {"temperature_K", p.temperature},
                                {"viscosity_Pa_s", p.viscosity},
                                {"min_separation_m", p.min_separation},
                                {"cutoff_m", p.cutoff},
                                {"initial_separation_m", p.initial_separation},
                                {"bond_separation_m", p.bond_separation},
                                {"bond_stiffness_factor", p.bond_stiffness_factor},
                                {"central_bonds", p.central_bonds},
                                {"bond_slip_force_N", p.bond_slip_force},
                                {"quench_steps", p.quench_steps},
                                {"step_fraction", p.step_fraction},
                                {"duration_diffusion_times", p.duration},
                                {"until_stable", p.until_stable},
                                {"stable_window_diffusion_times", p.stable_window},
                                {"stable_tolerance", p.stable_tolerance},
                                {"threads", p.threads},
                                {"seed", o.seed}};
        report["potential"] = {{"has_barrier", profile.has_barrier},
                               {"barrier_kT", profile.barrier_kT},
                               {"barrier_separation_m", profile.barrier_separation},
                               {"secondary_minimum_kT", profile.secondary_kT},
                               {"secondary_minimum_separation_m", profile.secondary_separation},
                               {"barrier_above_secondary_minimum_kT", profile.barrier_above_secondary_kT},
                               {"energy_at_cutoff_kT", profile.cutoff_kT},
                               {"energy_at_min_separation_kT",
                                dem::Dlvo::potential(p.dlvo(), p.radius, p.radius, p.min_separation).energy / p.kT()}};
        const double steps = static_cast<double>(r.status.step);
        report["results"] = {
            {"diffusion_coefficient_m2_per_s", d0},
            {"diffusion_time_s", p.diffusion_time()},
            {"time_step_s", r.time_step},
            {"time_step_diffusion_times", r.time_step / p.diffusion_time()},
            {"bond_stiffness_N_per_m", r.bond_stiffness},
            {"bond_thermal_stretch_m", std::sqrt(p.kT() / r.bond_stiffness)},
            {"steps", r.status.step},
            {"time_simulated_s", r.status.time},
            {"time_simulated_diffusion_times", r.status.reduced_time},
            {"stop", r.stable ? "stable" : "duration"},
            {"bonds", r.status.bonds},
            {"clusters", r.status.clusters},
            {"largest_cluster", r.status.largest_cluster},
            {"largest_cluster_fraction", static_cast<double>(r.status.largest_cluster) / static_cast<double>(n)},
            {"mean_coordination_bonds", r.mean_coordination},
            {"mean_coordination_eps_0.01", cn.mean()},
            {"volume_fraction", packing.volume_fraction()},
            {"msd_m2", r.status.msd},
            {"msd_diffusion_coefficient_m2_per_s", fitted_d},
            {"bd_seconds", r.status.seconds},
            {"particle_steps_per_second",
             r.status.seconds > 0 ? steps * static_cast<double>(n) / r.status.seconds : 0.0}};
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        report["seconds"] = seconds;
        io::write_report(dir / "report.json", report);
        if (!c.quiet)
          fmt::print(
              "{} spheres, psi0 {:g} mV (barrier {:.3g} kT, {:.3g} kT above the secondary minimum): t = {:.4g} a^2/D0 "
              "in {} steps, {} bonds (coordination {:.3f}), {} clusters, largest {} ({:.3g} particle-steps/s); wrote "
              "{} in {:.1f} s\n",
              n, 1e3 * p.surface_potential, profile.barrier_kT, profile.barrier_above_secondary_kT,
              r.status.reduced_time, r.status.step, r.status.bonds, r.mean_coordination, r.status.clusters,
              r.status.largest_cluster, r.status.seconds > 0 ? steps * static_cast<double>(n) / r.status.seconds : 0.0,
              c.out, seconds);
      });
}

}  // namespace packlab::cli
