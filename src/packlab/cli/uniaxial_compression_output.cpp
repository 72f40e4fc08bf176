#include "packlab/cli/uniaxial_compression_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "packlab/analyze/stress_strain.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"
#include "packlab/io/table.hpp"

namespace packlab::cli {

void write_uniaxial_compression_outputs(const mechanics::UniaxialCompressionResult& r,
                                        const mechanics::UniaxialCompressionOptions& /*o*/,
                                        const std::filesystem::path& dir, bool plots, bool write_model) {
  std::filesystem::create_directories(dir);
  io::PlotOptions plot;
  plot.enabled = plots;
  {
    io::write_text_atomically(dir / "curve.csv", io::to_csv(mechanics::curve_columns(r.curve)));
    const std::string curve = (dir / "curve.csv").string();
    io::make_plot(
        "stress_strain",
        {curve, "--modulus", fmt::format("{:.17g}", r.modulus.youngs_modulus), "--intercept",
         fmt::format("{:.17g}", r.modulus.intercept), "--fit-begin", fmt::format("{:.17g}", r.modulus.strain_begin),
         "--fit-end", fmt::format("{:.17g}", r.modulus.strain_end)},
        dir / "stress_strain.png", plot);
    io::make_plot("stress_strain", {curve, "--force-displacement"}, dir / "force_displacement.png", plot);
    io::make_plot("broken_bonds", {curve}, dir / "broken_bonds.png", plot);
  }
  if (!r.snapshots.empty()) {
    double lo = 0, hi = 0;
    for (const auto& s : r.snapshots)
      for (double e : s.bond_strain)
        if (std::isfinite(e)) {
          lo = std::min(lo, e);
          hi = std::max(hi, e);
        }
    const int bins = 60;
    if (!(hi > lo)) hi = lo + 1e-6;
    // One column per snapshot point: a strain and a stress request met at the same point of the
    // run are the same state (one column, not two of the same name).
    std::vector<const mechanics::UniaxialCompressionSnapshot*> points;
    for (const auto& s : r.snapshots)
      if (points.empty() || points.back()->strain != s.strain) points.push_back(&s);
    std::string csv = "strain_bin";
    for (const auto* s : points) csv += fmt::format(",fraction_at_{:.6g}", s->strain);
    csv += "\n";
    std::vector<std::vector<std::size_t>> h;
    std::vector<double> totals;
    for (const auto* point : points) {
      const auto& s = *point;
      h.push_back(analyze::histogram(s.bond_strain, lo, hi, bins));
      double t = 0;
      for (auto c : h.back()) t += static_cast<double>(c);
      totals.push_back(t > 0 ? t : 1.0);
    }
    for (int b = 0; b < bins; ++b) {
      csv += fmt::format("{:.17g}", lo + (b + 0.5) * (hi - lo) / bins);
      for (std::size_t s = 0; s < h.size(); ++s)
        csv += fmt::format(",{:.17g}", static_cast<double>(h[s][static_cast<std::size_t>(b)]) / totals[s]);
      csv += "\n";
    }
    io::write_text_atomically(dir / "bond_strain.csv", csv);
    io::make_plot("bond_strain", {(dir / "bond_strain.csv").string()}, dir / "bond_strain.png", plot);
    // requested_strain or requested_stress: the request the snapshot answers (the other empty).
    std::string ps =
        "strain,stress,type,particles,mean_xx,sd_xx,mean_yy,sd_yy,mean_zz,sd_zz,requested_strain,requested_stress\n";
    for (const auto& s : r.snapshots) {
      const std::string request =
          s.by_stress() ? fmt::format(",{:.17g}", s.requested_stress) : fmt::format("{:.17g},", s.requested_strain);
      for (const auto& t : analyze::stress_by_type(r.model, s.particle_stress))
        ps += fmt::format("{:.17g},{:.17g},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{}\n", s.strain,
                          s.stress, t.type, t.particles, t.mean[0], t.sd[0], t.mean[1], t.sd[1], t.mean[2], t.sd[2],
                          request);
    }
    io::write_text_atomically(dir / "particle_stress.csv", ps);
  }
  {
    std::string csv = "bond,time,strain,x,y,z\n";
    Packing breaks;
    breaks.box = r.model.box;
    auto& time_field = breaks.field_or_add("time");
    std::vector<double> times, strains;
    for (std::size_t k = 0; k < r.breaks.size(); ++k) {
      const auto& b = r.breaks[k];
      const double strain = r.break_strain[k];
      csv += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", b.bond, b.time, strain, b.position.x,
                         b.position.y, b.position.z);
      const auto& bonds = r.model.bonds;
      const double rb = 0.5 * std::min(r.model.radius[static_cast<std::size_t>(bonds.i[b.bond])],
                                       r.model.radius[static_cast<std::size_t>(bonds.j[b.bond])]);
      breaks.add(b.position, rb, 0);
      times.push_back(b.time);
      strains.push_back(strain);
    }
    time_field.values = times;
    breaks.field_or_add("strain").values = strains;
    io::write_text_atomically(dir / "broken_bonds.csv", csv);
    io::WriteOptions w;
    w.comment = "packlab test compress: positions of failed bonds (bond midpoints at failure)";
    io::write_packing(breaks, dir / "broken_bonds.vtu", w);
  }
  if (write_model) {
    io::WriteOptions w;
    w.comment = "packlab test compress: final state (bond state 1 = broken)";
    io::write_packing(r.model, dir / "model.vtu", w);
  }
}

}  // namespace packlab::cli
