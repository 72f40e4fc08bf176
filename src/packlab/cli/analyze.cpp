// packlab analyze FILE... --out DIR [--config FILE.toml] [every option of io::analyze_options as a flag:
//   --what all|cn|pores|doh|fabric|rdf --contact-eps 0.01 --rattler-threshold 4 --points N --band 0.005
//   --pore-definition pore_space|all_points --r0 R --fit-range XMIN,XMAX --fabric-bins 18 --box LX,LY,LZ
//   --periodic PX,PY,PZ --seed 1 --threads 0 ...] [--quiet] [--no-plots]
//
// Several files are realizations of one structure: coordination and fabric statistics are
// accumulated over all of them, pore-size points are pooled (equal numbers per file), and the
// report also lists every file's own values and their spread. DIR gets CSV tables, PNG plots
// and report.json (docs/analysis.md). Subcommands (e.g. `analyze rdf`) hang under this one;
// when one is used, this command's own callback does nothing.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "packlab/analyze/coordination.hpp"
#include "packlab/analyze/fabric.hpp"
#include "packlab/analyze/pore_size.hpp"
#include "packlab/analyze/rdf.hpp"
#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/cli/scrm_common.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

namespace {

struct AnalyzeOptions : io::AnalyzeRun {
  std::vector<std::string> files;
  std::string out;
  bool quiet = false;
  bool no_plots = false;
};

double mean_of(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

// Sample standard deviation (0 for fewer than two values).
double sd_of(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  const double m = mean_of(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

std::string g17(double v) { return fmt::format("{:.17g}", v); }

Packing read_one(const std::string& file, const AnalyzeOptions& opt) {
  io::ReadOptions ro;
  if (!opt.box.empty()) {
    if (opt.box.size() != 3) fail_input(fmt::format("box: must be LX,LY,LZ, got {} values", opt.box.size()));
    Box b;
    b.length = {opt.box[0], opt.box[1], opt.box[2]};
    for (int a = 0; a < 3; ++a)
      require(opt.box[a] > 0.0 && std::isfinite(opt.box[a]), fmt::format("box[{}]", "xyz"[a]), opt.box[a],
              "a positive length [m]");
    if (!opt.origin.empty() && opt.origin.size() != 3)
      fail_input(fmt::format("origin: must be X,Y,Z, got {} values", opt.origin.size()));
    if (!opt.origin.empty()) b.lo = {opt.origin[0], opt.origin[1], opt.origin[2]};
    // A user-given box is open unless --periodic says otherwise.
    b.periodic = {false, false, false};
    ro.box = b;
  } else if (!opt.origin.empty()) {
    fail_input("origin: needs --box (the origin of a user-given box)");
  }
  Packing p = io::read_packing(file, ro);
  if (!opt.periodic.empty()) {
    if (opt.periodic.size() != 3)
      fail_input(fmt::format("periodic: must be PX,PY,PZ, got {} values", opt.periodic.size()));
    for (int a = 0; a < 3; ++a) {
      require(opt.periodic[a] == 0 || opt.periodic[a] == 1, fmt::format("periodic[{}]", "xyz"[a]), opt.periodic[a],
              "0 or 1");
      p.box.periodic[a] = opt.periodic[a] == 1;
    }
    p.validate();
  }
  return p;
}

void run_analyze(const AnalyzeOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  // What to do.
  std::set<std::string> what;
  std::vector<std::string> listed;
  for (std::size_t begin = 0; begin <= opt.what.size();) {
    const std::size_t comma = std::min(opt.what.find(',', begin), opt.what.size());
    listed.push_back(opt.what.substr(begin, comma - begin));
    begin = comma + 1;
  }
  for (const auto& w : listed) {
    if (w == "all") {
      what.insert({"cn", "pores", "doh", "fabric", "rdf"});
    } else if (w == "cn" || w == "pores" || w == "doh" || w == "fabric" || w == "rdf") {
      what.insert(w);
    } else {
      fail_input("what = " + w + ": must be all, cn, pores, doh, fabric or rdf");
    }
  }
  if (what.count("doh")) what.insert("pores");
  const bool do_cn = what.count("cn") > 0, do_pores = what.count("pores") > 0, do_doh = what.count("doh") > 0,
             do_fabric = what.count("fabric") > 0, do_rdf = what.count("rdf") > 0;

  // Parameters first, so bad values fail before any file is read.
  const io::CoordinationSettings& cs = opt.coordination;
  analyze::Coordination cn(cs.contact_eps, cs.rattler_threshold, analyze::rattler_rule_from_name(cs.rattler_rule));
  const analyze::PoreSizeParams pp = opt.pores.params();
  analyze::PoreSize pores(pp);
  const analyze::DohFitOptions fo = opt.fit.options();
  if (do_doh && pp.definition != analyze::PoreDefinition::pore_space)
    fail_input("pore_definition = all_points: the degree-of-heterogeneity fit (--what doh, all) needs pore_space");
  analyze::Fabric fabric(cs.contact_eps, opt.fabric.fabric_bins, opt.fabric.fabric_without_rattlers,
                         cs.rattler_threshold);
  // RDF with the defaults of `packlab analyze rdf` (which has the options: --dr, --r-max, ...).
  analyze::RdfParams rdf_params;
  rdf_params.threads = pp.threads;
  rdf_params.validate();
  analyze::Rdf rdf(rdf_params);
  std::vector<Packing> rdf_packings;  // for the class volume fractions
  const std::filesystem::path dir = opt.out;
  const io::OutputFolder folder(dir);  // removed again if the first file is bad
  Random rng(opt.seed);

  nlohmann::json report = io::report_header("analyze");
  io::AnalyzeRun reported = opt;
  report["parameters"] = io::analyze_options(reported).json();
  report["parameters"]["what"] = std::vector<std::string>(what.begin(), what.end());
  report["parameters"]["points_used_per_file"] = pores.target_points();
  report["seed"] = opt.seed;
  report["files"] = opt.files;

  nlohmann::json per_file = nlohmann::json::array();
  std::vector<double> phi, cn_mean, cn_mean_nr, rattler_fraction, doh_a, doh_b;
  for (std::size_t f = 0; f < opt.files.size(); ++f) {
    const std::string& file = opt.files[f];
    if (!opt.quiet) fmt::print(stderr, "analyze: {} ({} of {})\n", file, f + 1, opt.files.size());
    const Packing packing = read_one(file, opt);
    nlohmann::json pf = {{"file", file}, {"particles", packing.size()}};
    phi.push_back(packing.volume_fraction());
    pf["volume_fraction"] = phi.back();
    if (do_cn) {
      analyze::Coordination one(opt.coordination.contact_eps, opt.coordination.rattler_threshold, cn.rattler_rule());
      one.compute(packing);
      cn.compute(packing, /*reset=*/f == 0);
      cn_mean.push_back(one.mean());
      cn_mean_nr.push_back(one.mean_without_rattlers());
      rattler_fraction.push_back(static_cast<double>(one.rattler_count()) / static_cast<double>(packing.size()));
      pf["mean_coordination"] = one.mean();
      pf["mean_coordination_without_rattlers"] = one.mean_without_rattlers();
      pf["rattlers"] = one.rattler_count();
      pf["contacts"] = one.contacts();
    }
    if (do_pores) {
      pores.compute(packing, rng, /*reset=*/f == 0);
      const int frame = static_cast<int>(f);
      pf["porosity_sampled"] = pores.porosity(frame);
      pf["pore_points"] = pores.counted_points(frame);
      pf["drawn_points"] = pores.drawn_points(frame);
      if (do_doh) {
        const analyze::DohFit d = analyze::fit_degree_of_heterogeneity(pores, fo, frame);
        doh_a.push_back(d.fit.a);
        doh_b.push_back(d.fit.b);
        pf["doh"] = {{"a", d.fit.a},
                     {"b", d.fit.b},
                     {"a_err", d.fit.a_err},
                     {"b_err", d.fit.b_err},
                     {"r2", d.fit.r2},
                     {"r0_m", d.r0},
                     {"fit_range_r_over_r0", {d.x_min, d.x_max}},
                     {"converged", d.fit.converged}};
      }
    }
    if (do_fabric) fabric.compute(packing, /*reset=*/f == 0);
    if (do_rdf) {
      rdf.accumulate(packing);
      rdf_packings.push_back(packing);
    }
    per_file.push_back(pf);
  }

  report["realizations"] = opt.files.size();
  report["volume_fraction"] = mean_of(phi);
  report["volume_fraction_sd"] = sd_of(phi);
  const io::PlotOptions plot_options{!opt.no_plots};
  std::vector<std::string> written;

  if (do_cn) {
    report["mean_coordination"] = cn.mean();
    report["mean_coordination_without_rattlers"] = cn.mean_without_rattlers();
    report["rattlers"] = cn.rattler_count();
    report["rattler_fraction"] = static_cast<double>(cn.rattler_count()) / static_cast<double>(cn.particle_count());
    report["coordination"] = {{"mean", cn.mean()},
                              {"mean_sd_between_files", sd_of(cn_mean)},
                              {"mean_without_rattlers", cn.mean_without_rattlers()},
                              {"mean_without_rattlers_sd_between_files", sd_of(cn_mean_nr)},
                              {"rattlers", cn.rattler_count()},
                              {"particles", cn.particle_count()},
                              {"distribution", cn.distribution()}};
    // Distribution table.
    std::ostringstream csv;
    csv << "# packlab analyze: particles by number of contacts, contact_eps = " << opt.coordination.contact_eps
        << ", over " << opt.files.size() << " file(s)\n";
    csv << "contacts,particles,fraction\n";
    const auto& dist = cn.distribution();
    for (std::size_t k = 0; k < dist.size(); ++k)
      csv << k << ',' << dist[k] << ',' << g17(static_cast<double>(dist[k]) / static_cast<double>(cn.particle_count()))
          << '\n';
    io::write_text_atomically(dir / "coordination.csv", csv.str());
    written.push_back("coordination.csv");
    // Per type and between types.
    const auto& types = cn.types();
    const auto means = cn.mean_by_type();
    const auto between = cn.between_types();
    std::ostringstream tcsv;
    tcsv << "type,particles,rattlers,mean_coordination";
    for (int t : types) tcsv << ",with_type_" << t;
    tcsv << '\n';
    nlohmann::json by_type = nlohmann::json::array();
    for (std::size_t a = 0; a < types.size(); ++a) {
      tcsv << types[a] << ',' << cn.particles_by_type()[a] << ',' << cn.rattlers_by_type()[a] << ',' << g17(means[a]);
      nlohmann::json with = nlohmann::json::object();
      for (std::size_t b = 0; b < types.size(); ++b) {
        tcsv << ',' << g17(between[a][b]);
        with[std::to_string(types[b])] = between[a][b];
      }
      tcsv << '\n';
      by_type.push_back({{"type", types[a]},
                         {"particles", cn.particles_by_type()[a]},
                         {"rattlers", cn.rattlers_by_type()[a]},
                         {"mean_coordination", means[a]},
                         {"contacts_per_particle_with_type", with}});
    }
    io::write_text_atomically(dir / "coordination_types.csv", tcsv.str());
    written.push_back("coordination_types.csv");
    report["coordination"]["by_type"] = by_type;
    if (io::make_plot("coordination", {(dir / "coordination.csv").string()}, dir / "coordination.png", plot_options))
      written.push_back("coordination.png");
  }

  if (do_pores) {
    const int grid = 201;
    const analyze::PoreSize::Curve curve = pores.curve(grid);
    nlohmann::json ps = {{"definition", opt.pores.pore_definition},
                         {"realizations", pores.frames()},
                         {"points_per_file", pores.target_points()},
                         {"points", pores.counted_points()},
                         {"drawn_points", pores.drawn_points()},
                         {"porosity_sampled", pores.porosity()},
                         {"porosity_sampled_std_error", pores.porosity_std_error()},
                         {"band_half_width", pores.band()},
                         {"confidence", opt.pores.confidence},
                         {"mean_radius_m", pores.mean_radius()},
                         {"largest_distance_m", pores.distances().back()}};
    analyze::DohFit d;
    if (do_doh) {
      d = analyze::fit_degree_of_heterogeneity(pores, fo);
      nlohmann::json doh = {{"a", d.fit.a},
                            {"b", d.fit.b},
                            {"a_err", d.fit.a_err},
                            {"b_err", d.fit.b_err},
                            {"a_ls_err", d.fit.a_ls_err},
                            {"b_ls_err", d.fit.b_ls_err},
                            {"r2", d.fit.r2},
                            {"r0_m", d.r0},
                            {"fit_range_r_over_r0", {d.x_min, d.x_max}},
                            {"fit_points", d.fit.points},
                            {"converged", d.fit.converged},
                            {"a_sd_between_files", sd_of(doh_a)},
                            {"b_sd_between_files", sd_of(doh_b)}};
      report["doh"] = doh;
    }
    std::ostringstream csv;
    csv << "# packlab analyze: cumulative pore-size distribution P(r_P > r), definition " << opt.pores.pore_definition
        << ", " << pores.counted_points() << " points over " << pores.frames() << " file(s); band: uniform "
        << opt.pores.confidence << " confidence band (DKW), half-width " << g17(pores.band())
        << "; r in the packing's length unit";
    if (do_doh) csv << "; fit: eq. 6 with a = " << g17(d.fit.a) << ", b = " << g17(d.fit.b) << ", r0 = " << g17(d.r0);
    csv << "\nr,probability,std_error,band_low,band_high" << (do_doh ? ",fit" : "") << '\n';
    for (std::size_t k = 0; k < curve.r.size(); ++k) {
      csv << g17(curve.r[k]) << ',' << g17(curve.probability[k]) << ',' << g17(curve.std_error[k]) << ','
          << g17(curve.band_low[k]) << ',' << g17(curve.band_high[k]);
      if (do_doh) csv << ',' << g17(analyze::pore_erf_model(curve.r[k] / d.r0, d.fit.a, d.fit.b));
      csv << '\n';
    }
    io::write_text_atomically(dir / "pore_size.csv", csv.str());
    written.push_back("pore_size.csv");
    report["pore_size"] = ps;
    std::vector<std::string> args{(dir / "pore_size.csv").string()};
    if (do_doh) {
      args.insert(args.end(), {"--a", g17(d.fit.a), "--b", g17(d.fit.b), "--r0", g17(d.r0), "--fit-min",
                               g17(d.x_min * d.r0), "--fit-max", g17(d.x_max * d.r0)});
    }
    if (io::make_plot("pore_size", args, dir / "pore_size.png", plot_options)) written.push_back("pore_size.png");
  }

  if (do_fabric) {
    const auto& t = fabric.tensor();
    const auto dev = fabric.deviator();
    report["fabric"] = {
        {"tensor", {{t[0][0], t[0][1], t[0][2]}, {t[1][0], t[1][1], t[1][2]}, {t[2][0], t[2][1], t[2][2]}}},
        {"deviator",
         {{dev[0][0], dev[0][1], dev[0][2]}, {dev[1][0], dev[1][1], dev[1][2]}, {dev[2][0], dev[2][1], dev[2][2]}}},
        {"eigenvalues", fabric.eigenvalues()},
        {"anisotropy", fabric.anisotropy()},
        {"contacts", fabric.contacts()},
        {"without_rattlers", opt.fabric.fabric_without_rattlers}};
    std::ostringstream csv;
    csv << "# packlab analyze: density of |n . e| of the contact normals n on [0, 1] (1 = isotropic), "
        << fabric.contacts() << " contacts\n";
    csv << "abs_cos,density_x,density_y,density_z\n";
    const auto centers = fabric.bin_centers();
    const auto& dens = fabric.normal_density();
    for (std::size_t k = 0; k < centers.size(); ++k)
      csv << g17(centers[k]) << ',' << g17(dens[k][0]) << ',' << g17(dens[k][1]) << ',' << g17(dens[k][2]) << '\n';
    io::write_text_atomically(dir / "contact_normals.csv", csv.str());
    written.push_back("contact_normals.csv");
  }

  if (do_rdf) {
    std::vector<double> cvf(rdf.classes(), 0.0);
    for (const auto& p : rdf_packings) {
      const auto c = class_volume_fractions(p, rdf.class_radius());
      for (std::size_t k = 0; k < c.size() && k < cvf.size(); ++k)
        cvf[k] += c[k] / static_cast<double>(rdf_packings.size());
    }
    report["rdf"] = write_rdf_outputs(rdf, cvf, dir, /*partial=*/false, !opt.no_plots);
    for (const char* name : {"rdf.csv", "windows.csv"}) written.push_back(name);
  }

  report["per_file"] = per_file;
  report["outputs"] = written;
  report["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::write_report(dir / "report.json", report);

  if (!opt.quiet) {
    fmt::print("analyzed {} file(s), volume fraction {:.6f}\n", opt.files.size(), mean_of(phi));
    if (do_cn)
      fmt::print("mean coordination  {:.4f} (without {} rattlers: {:.4f}; contact eps {:g})\n", cn.mean(),
                 cn.rattler_count(), cn.mean_without_rattlers(), opt.coordination.contact_eps);
    if (do_pores)
      fmt::print("pore size          {} points, porosity {:.4f} +- {:.4f}, band +-{:.4f} at {:g}\n",
                 pores.counted_points(), pores.porosity(), pores.porosity_std_error(), pores.band(),
                 opt.pores.confidence);
    if (do_doh) {
      const auto& doh = report["doh"];
      fmt::print("degree of heterogeneity a = {:.4f} +- {:.4f}, b = {:.4f} +- {:.4f}, R^2 = {:.5f}\n",
                 doh["a"].get<double>(), doh["a_err"].get<double>(), doh["b"].get<double>(), doh["b_err"].get<double>(),
                 doh["r2"].get<double>());
    }
    if (do_fabric) fmt::print("fabric anisotropy  {:.4f} ({} contacts)\n", fabric.anisotropy(), fabric.contacts());
    if (do_rdf)
      fmt::print("rdf                contact value g(2a+) = {:.4g} (rdf.csv; options in packlab analyze rdf)\n",
                 rdf.contact_value(0, 0));
    fmt::print("wrote {}/report.json in {:.2f} s\n", opt.out, report["seconds"].get<double>());
  }
}

}  // namespace

CLI::App* add_analyze(CLI::App& app) {
  auto opt = std::make_shared<AnalyzeOptions>();
  auto* cmd = app.add_subcommand("analyze",
                                 "Microstructure of packings: coordination, pore-size distribution and degree of "
                                 "heterogeneity, fabric; several files are realizations");
  cmd->require_subcommand(0, 1);
  cmd->add_option("files", opt->files, "Packing files (any format packlab reads)");
  auto flags = std::make_shared<OptionFlags>(cmd, io::analyze_options(*opt));
  cmd->add_option("--out", opt->out, "Output folder for the tables, plots and report.json");
  cmd->add_flag("--quiet", opt->quiet, "No progress or summary output");
  cmd->add_flag("--no-plots", opt->no_plots, "Write tables and report only");
  cmd->callback([opt, cmd, flags] {
    if (!cmd->get_subcommands().empty()) return;  // e.g. `packlab analyze rdf ...` did the work
    flags->load();
    flags->schema().validate();
    if (opt->files.empty()) fail_input("analyze: at least one packing FILE is required");
    if (opt->out.empty()) fail_input("analyze: --out DIR is required");
    run_analyze(*opt);
  });
  return cmd;
}

}  // namespace packlab::cli
