// The option sets of the analyses (io/options.hpp): the Python analysis classes and
// `packlab analyze`, `packlab analyze rdf`.
#include <fmt/format.h>

#include "packlab/core/error.hpp"
#include "packlab/io/options.hpp"

namespace packlab::io {

void add_coordination_options(ConfigSchema& schema, CoordinationSettings& s) {
  schema.number("contact_eps", s.contact_eps, "Contact when the centre distance is below (1 + eps)(r_i + r_j)")
      .range({0.0, 1.0, false, true})
      .integer("rattler_threshold", s.rattler_threshold, "Rattler: fewer contacts than this")
      .range({0.0, 100.0, false, false})
      .text("rattler_rule", s.rattler_rule,
            "iterative: remove rattlers until all others keep the threshold (k-core); single_pass: flag once");
}

ConfigSchema coordination_options(CoordinationSettings& s) {
  ConfigSchema schema("Coordination", "Coordination numbers and rattlers (docs/analysis.md).", "Coordination");
  add_coordination_options(schema, s);
  return schema;
}

analyze::PoreSizeParams PoreSizeSettings::params() const {
  analyze::PoreSizeParams p;
  p.points = points;
  p.band = band;
  p.confidence = confidence;
  p.definition = analyze::pore_definition_from_name(pore_definition);
  p.wall_margin = wall_margin;
  p.threads = threads;
  return p;
}

void add_pore_size_options(ConfigSchema& schema, PoreSizeSettings& s) {
  schema.integer("points", s.points, "Pore-size test points per packing that count (0 = from band)")
      .range({0.0, 1e9, false, false})
      .number("band", s.band, "Target half-width of the uniform confidence band on P(r_P > r)")
      .range({0.0, 0.5, true, false})
      .number("confidence", s.confidence, "Confidence level of that band")
      .range({0.0, 1.0, true, true})
      .text("pore_definition", s.pore_definition,
            "pore_space: over points outside the particles (P(0) = 1); all_points: over all points")
      .number("wall_margin", s.wall_margin,
              "Open axes: no test points closer than this to a wall; < 0 = one mean diameter")
      .unit("m")
      .integer("threads", s.threads, "OpenMP threads (0 = all cores)")
      .range({0.0, 1024.0, false, false});
}

ConfigSchema pore_size_options(PoreSizeSettings& s) {
  ConfigSchema schema("PoreSize", "Pore-size distribution by the exclusion probability (docs/analysis.md).",
                      "PoreSize");
  add_pore_size_options(schema, s);
  return schema;
}

analyze::DohFitOptions DohFitSettings::options() const {
  analyze::DohFitOptions fo;
  fo.r0 = r0;
  fo.p_min = fit_p_min;
  fo.grid = fit_grid;
  if (!fit_range.empty()) {
    if (fit_range.size() != 2) fail_input(fmt::format("fit_range: must be XMIN,XMAX, got {} values", fit_range.size()));
    fo.x_min = fit_range[0];
    fo.x_max = fit_range[1];
    require(fo.x_max > fo.x_min, "fit_range max", fo.x_max, fmt::format("greater than fit_range min = {:g}", fo.x_min));
  }
  return fo;
}

void add_doh_fit_options(ConfigSchema& schema, DohFitSettings& s) {
  schema.number("r0", s.r0, "Length unit r0 of eq. 6; 0 = mean particle radius")
      .unit("m")
      .range(ranges::non_negative)
      .numbers("fit_range", s.fit_range, "Fit eq. 6 over XMIN <= r/r0 <= XMAX (default 0 to P = fit_p_min)")
      .number("fit_p_min", s.fit_p_min, "Default fit range ends where P(r_P > r) falls to this")
      .range({0.0, 1.0, true, true})
      .integer("fit_grid", s.fit_grid, "Equally spaced r/r0 values at which eq. 6 is fitted")
      .range({3.0, 1e6, false, false});
}

ConfigSchema doh_fit_options(DohFitSettings& s) {
  ConfigSchema schema("PoreSize.fit_doh", "The error-function fit of eq. 6 (degree of heterogeneity).", "fit_doh");
  add_doh_fit_options(schema, s);
  return schema;
}

void add_fabric_options(ConfigSchema& schema, FabricSettings& s) {
  schema.integer("fabric_bins", s.fabric_bins, "Bins of the contact-normal distribution")
      .range({1.0, 10000.0, false, false})
      .boolean("fabric_without_rattlers", s.fabric_without_rattlers, "Leave rattlers' contacts out of the fabric");
}

ConfigSchema fabric_options(CoordinationSettings& c, FabricSettings& s) {
  ConfigSchema schema("Fabric", "Fabric tensor of the contact normals (docs/analysis.md).", "Fabric");
  schema.number("contact_eps", c.contact_eps, "Contact when the centre distance is below (1 + eps)(r_i + r_j)")
      .range({0.0, 1.0, false, true})
      .integer("rattler_threshold", c.rattler_threshold, "Rattler: fewer contacts than this")
      .range({0.0, 100.0, false, false});
  add_fabric_options(schema, s);
  return schema;
}

ConfigSchema analyze_options(AnalyzeRun& r) {
  ConfigSchema schema("analyze", "Microstructure of packings (docs/analysis.md); several files are realizations.",
                      "Coordination, PoreSize, PoreSize.fit_doh, Fabric");
  schema.text("what", r.what, "all, cn, pores, doh, fabric or rdf (several: comma-separated)").command_only();
  add_coordination_options(schema, r.coordination);
  add_pore_size_options(schema, r.pores);
  add_doh_fit_options(schema, r.fit);
  add_fabric_options(schema, r.fabric);
  schema.numbers("box", r.box, "Box edges LX,LY,LZ for files without a box (or to override it); open unless periodic")
      .unit("m")
      .command_only()
      .numbers("origin", r.origin, "Lower corner X,Y,Z of that box (default 0,0,0)")
      .unit("m")
      .command_only()
      .numbers("periodic", r.periodic, "Periodicity flags PX,PY,PZ (0 or 1) overriding the files'")
      .command_only()
      .integer("seed", r.seed, "Seed of the pore-size test points")
      .command_only();
  return schema;
}

analyze::RdfParams RdfSettings::validated() const {
  analyze::RdfParams p = params;
  p.edge = analyze::edge_correction_from_name(edge);
  p.validate();
  return p;
}

ConfigSchema rdf_options(RdfSettings& s) {
  ConfigSchema schema("analyze rdf", "Radial distribution function, K-function, windows (docs/analysis.md).", "Rdf");
  schema.number("dr", s.params.dr, "Bin width in units of the (largest) radius a")
      .range(ranges::positive)
      .number("r_max", s.params.r_max, "Largest distance in units of a")
      .range(ranges::positive)
      .number("window_radius", s.params.window_radius, "Radius of the counting windows in units of a")
      .range(ranges::positive)
      .text("edge", s.edge,
            "Edge correction: auto (toroidal when every axis is periodic), toroidal, ripley, "
            "minus_sampling")
      .integer("threads", s.params.threads, "OpenMP threads (0 = all cores)")
      .range({0.0, 1024.0, false, false})
      .boolean("partial", s.partial, "Also the partial RDFs g_km of every pair of size classes")
      .command_only();
  return schema;
}

}  // namespace packlab::io
