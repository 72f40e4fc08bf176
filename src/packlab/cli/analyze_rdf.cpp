// packlab analyze rdf FILE... [--partial] [--dr 0.01] [--r-max 8] [--window-radius 2.5]
//   [--edge auto|toroidal|ripley|minus-sampling] [--threads T] --out DIR
// Several files are realizations of the same structure: their RDFs are averaged (computed in
// parallel, merged in file order).
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <omp.h>

#include <chrono>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>

#include "packlab/analyze/reference_rdf.hpp"
#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/cli/scrm_common.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/parallel_errors.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

std::vector<double> class_volume_fractions(const Packing& packing, const std::vector<double>& class_radius) {
  std::vector<double> c(class_radius.size(), 0.0);
  for (double r : packing.radius) {
    std::size_t k = 0;
    while (k + 1 < class_radius.size() && r < class_radius[k] * (1.0 - 1e-6)) ++k;
    c[k] += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  }
  for (double& v : c) v /= packing.box.volume();
  return c;
}

nlohmann::json write_rdf_outputs(const analyze::Rdf& rdf, const std::vector<double>& cvf,
                                 const std::filesystem::path& dir, bool partial, bool plots) {
  namespace ref = analyze::reference;
  const int nc = rdf.classes();
  const std::vector<double>& a = rdf.class_radius();
  double c_total = 0.0;
  for (double c : cvf) c_total += c;
  const std::vector<double> R = rdf.reduced_r();
  const auto K = rdf.k_function(), G = rdf.g(), I = rdf.shell_count();
  {
    std::ostringstream csv;
    csv << fmt::format("# packlab {} rdf: R = r/a with a = {:.17g} m (largest class radius), realizations {}\n",
                       io::version(), a[0], rdf.realizations());
    csv << "r,R,K,g,I,well_stirred,willis,percus_yevick\n";
    // The full Percus-Yevick curve of one size (nan for mixtures, whose partial curves are not computed).
    std::vector<double> py_curve(R.size(), std::numeric_limits<double>::quiet_NaN());
    if (nc == 1 && c_total < 1.0) py_curve = ref::percus_yevick(R, c_total);  // R = b dr > 0 (Rdf::reduced_r)
    for (std::size_t b = 0; b < R.size(); ++b)
      csv << fmt::format("{:.10g},{:.6g},{:.10g},{:.10g},{:.10g},{},{:.10g},{:.10g}\n", R[b] * a[0], R[b], K[b], G[b],
                         I[b], ref::well_stirred(R[b], 1.0), nc == 1 ? ref::willis(R[b], 1.0, c_total) : 1.0,
                         py_curve[b]);
    io::write_text_atomically(dir / "rdf.csv", csv.str());
  }
  nlohmann::json out;
  out["realizations"] = rdf.realizations();
  out["dr_over_a"] = rdf.params().dr;
  out["rmax_over_a"] = rdf.params().r_max;
  out["edge_correction"] = analyze::edge_correction_name(rdf.params().edge);
  out["class_radius_m"] = a;
  out["class_volume_fraction"] = cvf;
  const auto py = ref::percus_yevick_contact_mixture(a, cvf);
  nlohmann::json contacts = nlohmann::json::array();
  for (int k = 0; k < nc; ++k)
    for (int m = k; m < nc; ++m) {
      const auto pk = rdf.peaks(k, m, 4);
      std::vector<double> scaled;
      for (double r : pk) scaled.push_back((r * a[0] - a[k]) / a[m] + 1.0);
      contacts.push_back({{"k", k},
                          {"m", m},
                          {"contact_value", rdf.contact_value(k, m)},
                          {"percus_yevick", py[k][m]},
                          {"peaks_R", pk},
                          {"peaks_R_km", scaled}});
    }
  out["pairs"] = contacts;
  out["contact_value"] = rdf.contact_value(0, 0);
  out["peaks_R"] = rdf.peaks(-1, -1, 4);
  if (partial && nc > 1) {
    std::ostringstream csv;
    csv << fmt::format("# packlab {} partial rdf: class k around class m, R_km = (r - a_k)/a_m + 1\n", io::version());
    csv << "k,m,r,R,R_km,K,g,I,willis_partial\n";
    for (int k = 0; k < nc; ++k)
      for (int m = k; m < nc; ++m) {
        const auto Kk = rdf.k_function(k, m), Gk = rdf.g(k, m), Ik = rdf.shell_count(k, m);
        for (std::size_t b = 0; b < R.size(); ++b) {
          const double r = R[b] * a[0];
          const double rkm = (r - a[k]) / a[m] + 1.0;
          csv << fmt::format("{},{},{:.10g},{:.6g},{:.6g},{:.10g},{:.10g},{:.10g},{:.10g}\n", k, m, r, R[b], rkm, Kk[b],
                             Gk[b], Ik[b], ref::willis_partial(rkm, py[k][m]));
        }
      }
    io::write_text_atomically(dir / "rdf_partial.csv", csv.str());
  }
  {
    std::ostringstream csv;
    csv << "# packlab window histogram: fraction of windows (radius R_h a_k around each centre) holding n others\n";
    csv << "n,p_all";
    for (int k = 0; k < nc; ++k) csv << ",p_class" << k;
    csv << "\n";
    std::vector<std::vector<double>> p{rdf.window_histogram(-1)};
    std::size_t len = p[0].size();
    for (int k = 0; k < nc; ++k) {
      p.push_back(rdf.window_histogram(k));
      len = std::max(len, p.back().size());
    }
    for (std::size_t c = 0; c < len; ++c) {
      csv << c;
      for (const auto& h : p) csv << "," << (c < h.size() ? h[c] : 0.0);
      csv << "\n";
    }
    io::write_text_atomically(dir / "windows.csv", csv.str());
    double mean = 0.0, var = 0.0;
    for (std::size_t c = 0; c < p[0].size(); ++c) mean += static_cast<double>(c) * p[0][c];
    for (std::size_t c = 0; c < p[0].size(); ++c)
      var += (static_cast<double>(c) - mean) * (static_cast<double>(c) - mean) * p[0][c];
    out["windows"] = {
        {"radius_over_a", rdf.params().window_radius}, {"count", rdf.windows(-1)}, {"mean", mean}, {"variance", var}};
  }
  io::PlotOptions po;
  po.enabled = plots;
  std::vector<std::string> args{(dir / "rdf.csv").string(), "--phi", fmt::format("{:.6g}", c_total)};
  io::make_plot("rdf", args, dir / "rdf.png", po);
  if (partial && nc > 1)
    io::make_plot("rdf_partial", {(dir / "rdf_partial.csv").string()}, dir / "rdf_partial.png", po);
  io::make_plot("windows", {(dir / "windows.csv").string()}, dir / "windows.png", po);
  return out;
}

void add_analyze_rdf(CLI::App& analyze) {
  struct Options : io::RdfSettings {
    std::vector<std::string> files;
    std::string out;
    bool no_plots = false;
    bool quiet = false;
    std::unique_ptr<OptionFlags> flags;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = analyze.add_subcommand(
      "rdf", "Radial distribution function g(r), K-function, partial g_km, shell count I(r), window histograms");
  cmd->add_option("files", opt->files, "Packings (several = realizations, averaged)")->required();
  opt->flags = std::make_unique<OptionFlags>(cmd, io::rdf_options(*opt));
  cmd->add_option("--out", opt->out, "Output folder")->required();
  cmd->add_flag("--no-plots", opt->no_plots, "Do not write PNG plots");
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt] {
    const auto t0 = std::chrono::steady_clock::now();
    opt->flags->load();
    opt->flags->schema().validate();
    opt->params = opt->validated();
    const std::size_t nf = opt->files.size();
    std::vector<Packing> packings(nf);
    for (std::size_t f = 0; f < nf; ++f) packings[f] = io::read_packing(opt->files[f]);
    const io::OutputFolder folder(opt->out);  // after the inputs; removed again on a later error
    std::vector<analyze::Rdf> parts(nf, analyze::Rdf(opt->params));
    // Realizations in parallel, one thread each; merged in file order (deterministic).
    const int threads = opt->params.threads > 0 ? opt->params.threads : omp_get_max_threads();
    // Bad input names its file; an allocation failure stays a bad_alloc (main's out-of-memory
    // message); either leaves the region through ParallelErrors, not std::terminate.
    ParallelErrors errors;
#pragma omp parallel for schedule(dynamic) num_threads(threads) if (nf > 1)
    for (long f = 0; f < static_cast<long>(nf); ++f)
      errors.run(f, [&] {
        analyze::RdfParams p = opt->params;
        p.threads = nf > 1 ? 1 : threads;
        try {
          analyze::Rdf r(p);
          r.compute(packings[static_cast<std::size_t>(f)]);
          parts[static_cast<std::size_t>(f)] = r;
        } catch (const InputError& e) {
          fail_input(opt->files[static_cast<std::size_t>(f)] + ": " + e.what());
        }
      });
    errors.rethrow();
    analyze::Rdf total(opt->params);
    for (const auto& r : parts) total.add(r);
    std::vector<double> cvf(total.classes(), 0.0);
    for (const auto& p : packings) {
      const auto c = class_volume_fractions(p, total.class_radius());
      for (std::size_t k = 0; k < c.size(); ++k) cvf[k] += c[k] / static_cast<double>(nf);
    }
    nlohmann::json report = io::report_header("analyze rdf");
    report["parameters"] = opt->flags->schema().json();
    report["parameters"]["files"] = opt->files;
    report["results"] = write_rdf_outputs(total, cvf, opt->out, opt->partial, !opt->no_plots);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report["seconds"] = seconds;
    io::write_report(std::filesystem::path(opt->out) / "report.json", report);
    if (!opt->quiet) {
      fmt::print("{} realization(s), {} size class(es): contact value g(2a+) = {:.4g}, peaks at R = {}\n", nf,
                 total.classes(), total.contact_value(0, 0), fmt::join(total.peaks(-1, -1, 4), ", "));
      fmt::print("wrote {}/rdf.csv, windows.csv and report.json in {:.2f} s\n", opt->out, seconds);
    }
  });
}

}  // namespace packlab::cli
