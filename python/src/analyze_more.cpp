// Analyses of issues #3/#4/#5: RDF (with the analytic references), pore-size distribution and
// its erf fit (degree of heterogeneity), fabric tensor, CN(q) inflection and power-law fits.
#include "common.hpp"
#include "packlab/analyze/fabric.hpp"
#include "packlab/analyze/fits.hpp"
#include "packlab/analyze/inflection.hpp"
#include "packlab/analyze/pore_size.hpp"
#include "packlab/analyze/power_law.hpp"
#include "packlab/analyze/rdf.hpp"
#include "packlab/analyze/reference_rdf.hpp"
#include "packlab/core/random.hpp"

namespace packlab::python {

namespace {
py::object namespace_of(py::dict values) { return py::module_::import("types").attr("SimpleNamespace")(**values); }
}  // namespace

void bind_analyze_later(py::module_& m) {
  using namespace analyze;

  // --- rdf (issue 4) ---
  py::class_<Rdf>(m, "Rdf", R"doc(
Radial distribution function g(r) and partial g_km via the K-function (`packlab analyze rdf`).
Rdf(dr=0.01, r_max=8.0, window_radius=2.5, edge="automatic", threads=0): dr and r_max in units
of the reference radius a (the largest class radius); edge: "automatic" (toroidal when every
axis is periodic), "toroidal", "ripley" or "minus_sampling". compute(packing) forgets earlier
realizations, accumulate(packing) adds one. Class k = -1 means all particles.
)doc")
      .def(py::init([](double dr, double r_max, double window_radius, const std::string& edge, int threads) {
             RdfParams p;
             p.dr = dr;
             p.r_max = r_max;
             p.window_radius = window_radius;
             p.edge = edge_correction_from_name(edge);
             p.threads = threads;
             p.validate();
             return Rdf(p);
           }),
           py::kw_only(), py::arg("dr") = 0.01, py::arg("r_max") = 8.0, py::arg("window_radius") = 2.5,
           py::arg("edge") = "automatic", py::arg("threads") = 0)
      .def(
          "compute",
          [](py::object self, const Packing& p) {
            {
              py::gil_scoped_release nogil;
              self.cast<Rdf&>().compute(p);
            }
            return self;
          },
          py::arg("packing"))
      .def(
          "accumulate",
          [](py::object self, const Packing& p) {
            {
              py::gil_scoped_release nogil;
              self.cast<Rdf&>().accumulate(p);
            }
            return self;
          },
          py::arg("packing"))
      .def_property_readonly("realizations", &Rdf::realizations)
      .def_property_readonly("classes", &Rdf::classes)
      .def_property_readonly("class_radius", &Rdf::class_radius, "Radius of each size class, largest first [m].")
      .def_property_readonly("reference_radius", &Rdf::reference_radius, "a [m]")
      .def_property_readonly("r", [](const Rdf& r) { return to_numpy(r.reduced_r()); }, "Bin centres r/a.")
      .def("g", [](const Rdf& r, int k, int l) { return to_numpy(r.g(k, l)); }, py::arg("k") = -1, py::arg("m") = -1,
           "g(r) (partial g_km for classes k, m).")
      .def("k_function", [](const Rdf& r, int k, int l) { return to_numpy(r.k_function(k, l)); }, py::arg("k") = -1,
           py::arg("m") = -1)
      .def("shell_count", [](const Rdf& r, int k, int l) { return to_numpy(r.shell_count(k, l)); }, py::arg("k") = -1,
           py::arg("m") = -1)
      .def("contact_value", &Rdf::contact_value, py::arg("k") = -1, py::arg("m") = -1, "g at contact, g(2a+).")
      .def("peaks", &Rdf::peaks, py::arg("k") = -1, py::arg("m") = -1, py::arg("count") = 4,
           "Positions r/a of the first peaks.")
      .def("window_histogram", [](const Rdf& r, int k) { return to_numpy(r.window_histogram(k)); },
           py::arg("k") = -1, "p(n): fraction of windows holding n centres.")
      .def("windows", &Rdf::windows, py::arg("k") = -1);

  auto ref = m.def_submodule("reference", "Analytic reference RDFs (well-stirred, Willis, Percus-Yevick).");
  ref.def("well_stirred", &reference::well_stirred, py::arg("r"), py::arg("a"));
  ref.def("willis", &reference::willis, py::arg("r"), py::arg("a"), py::arg("c"), py::arg("use_original") = false,
          "Willis' g(r) for spheres of radius a at volume fraction c.");
  ref.def("percus_yevick_contact", &reference::percus_yevick_contact, py::arg("c"), "g(2a+) of Percus-Yevick.");
  ref.def("percus_yevick_contact_mixture", &reference::percus_yevick_contact_mixture, py::arg("radius"),
          py::arg("volume_fraction"));

  // --- pore size (issue 5) ---
  py::class_<PoreSize>(m, "PoreSize", R"doc(
Pore-size distribution P(r_P > r) by the exclusion probability (doh-elastic-properties eq. 6).
PoreSize(points=0, band=0.005, confidence=0.95, definition="pore_space", wall_margin=-1,
threads=0): points counted per packing (0 = from the confidence band), definition
"pore_space" or "all_points", wall_margin [m] along open axes (< 0 = one mean diameter).
compute(packing, seed=1, reset=True); curve() -> dict r [m], probability, std_error,
band_low, band_high; fit_doh() -> the erf fit giving the degree of heterogeneity (a, b).
)doc")
      .def(py::init([](long points, double band, double confidence, const std::string& definition,
                       double wall_margin, int threads) {
             PoreSizeParams p;
             p.points = points;
             p.band = band;
             p.confidence = confidence;
             p.definition = pore_definition_from_name(definition);
             p.wall_margin = wall_margin;
             p.threads = threads;
             return PoreSize(p);
           }),
           py::kw_only(), py::arg("points") = 0, py::arg("band") = 0.005, py::arg("confidence") = 0.95,
           py::arg("definition") = "pore_space", py::arg("wall_margin") = -1.0, py::arg("threads") = 0)
      .def(
          "compute",
          [](py::object self, const Packing& p, std::uint64_t seed, bool reset) {
            {
              py::gil_scoped_release nogil;
              Random rng(seed);
              self.cast<PoreSize&>().compute(p, rng, reset);
            }
            return self;
          },
          py::arg("packing"), py::kw_only(), py::arg("seed") = 1, py::arg("reset") = true)
      .def(
          "curve",
          [](const PoreSize& s, int points, int frame) {
            PoreSize::Curve c = s.curve(points, frame);
            py::dict d;
            d["r"] = to_numpy(std::move(c.r));
            d["probability"] = to_numpy(std::move(c.probability));
            d["std_error"] = to_numpy(std::move(c.std_error));
            d["band_low"] = to_numpy(std::move(c.band_low));
            d["band_high"] = to_numpy(std::move(c.band_high));
            return d;
          },
          py::arg("points") = 201, py::arg("frame") = -1)
      .def("probability", &PoreSize::probability, py::arg("r"), py::arg("frame") = -1)
      .def("distances", [](const PoreSize& s, int frame) { return to_numpy(std::vector<double>(s.distances(frame))); },
           py::arg("frame") = -1, "Distance of each counted point to the nearest particle surface [m].")
      .def_property_readonly("frames", &PoreSize::frames)
      .def("porosity", &PoreSize::porosity, py::arg("frame") = -1)
      .def("porosity_std_error", &PoreSize::porosity_std_error, py::arg("frame") = -1)
      .def("counted_points", &PoreSize::counted_points, py::arg("frame") = -1)
      .def("mean_radius", &PoreSize::mean_radius, py::arg("frame") = -1)
      .def(
          "fit_doh",
          [](const PoreSize& s, double r0, double x_min, double x_max, double p_min, int grid, int frame) {
            DohFitOptions o;
            o.r0 = r0;
            o.x_min = x_min;
            o.x_max = x_max;
            o.p_min = p_min;
            o.grid = grid;
            const DohFit f = fit_degree_of_heterogeneity(s, o, frame);
            py::dict d;
            d["a"] = f.fit.a;
            d["b"] = f.fit.b;
            d["a_err"] = f.fit.a_err;
            d["b_err"] = f.fit.b_err;
            d["r2"] = f.fit.r2;
            d["points"] = f.fit.points;
            d["converged"] = f.fit.converged;
            d["r0"] = f.r0;
            d["x_min"] = f.x_min;
            d["x_max"] = f.x_max;
            return namespace_of(d);
          },
          py::kw_only(), py::arg("r0") = 0.0, py::arg("x_min") = 0.0, py::arg("x_max") = 0.0, py::arg("p_min") = 1e-3,
          py::arg("grid") = 100, py::arg("frame") = -1,
          "Error-function fit of eq. 6: a (degree of heterogeneity) and b in units of r0 [m] (0 = mean radius).");
  m.def("pore_erf_model", &pore_erf_model, py::arg("x"), py::arg("a"), py::arg("b"), "The eq. 6 model P(x; a, b).");

  // --- fabric (issue 5) ---
  py::class_<Fabric>(m, "Fabric", R"doc(
Fabric tensor of the contact normals. Fabric(contact_eps=0.01, bins=18, exclude_rattlers=False,
rattler_threshold=4); compute(packing, reset=True); tensor (3 x 3, trace 1), deviator,
eigenvalues (descending), anisotropy, contacts, normal_density, bin_centers.
)doc")
      .def(py::init<double, int, bool, int>(), py::kw_only(), py::arg("contact_eps") = 0.01, py::arg("bins") = 18,
           py::arg("exclude_rattlers") = false, py::arg("rattler_threshold") = 4)
      .def(
          "compute",
          [](py::object self, const Packing& p, bool reset) {
            {
              py::gil_scoped_release nogil;
              self.cast<Fabric&>().compute(p, reset);
            }
            return self;
          },
          py::arg("packing"), py::arg("reset") = true)
      .def_property_readonly("tensor", [](const Fabric& f) { return py::array(py::cast(f.tensor())); })
      .def_property_readonly("deviator", [](const Fabric& f) { return py::array(py::cast(f.deviator())); })
      .def_property_readonly("eigenvalues", [](const Fabric& f) { return py::array(py::cast(f.eigenvalues())); })
      .def_property_readonly("anisotropy", &Fabric::anisotropy)
      .def_property_readonly("contacts", &Fabric::contacts)
      .def_property_readonly("normal_density", [](const Fabric& f) { return py::array(py::cast(f.normal_density())); })
      .def_property_readonly("bin_centers", [](const Fabric& f) { return to_numpy(f.bin_centers()); });

  // --- fits (issues 3 and 5) ---
  m.def(
      "find_inflection",
      [](const std::vector<double>& x, const std::vector<double>& y, double window_widths, int min_points) {
        InflectionOptions o;
        o.window_widths = window_widths;
        o.min_points = min_points;
        const Inflection f = analyze::find_inflection(x, y, o);
        py::dict d;
        d["found"] = f.found;
        d["message"] = f.message;
        d["x"] = f.x;
        d["x_err"] = f.x_err;
        d["y"] = f.y;
        d["y_err"] = f.y_err;
        d["slope"] = f.slope;
        d["slope_err"] = f.slope_err;
        d["x_lo"] = f.x_lo;
        d["x_hi"] = f.x_hi;
        d["points"] = f.points;
        d["r2"] = f.r2;
        d["a"] = f.a;
        d["b"] = f.b;
        d["c"] = f.c;
        d["width"] = f.width;
        return namespace_of(d);
      },
      py::arg("x"), py::arg("y"), py::kw_only(), py::arg("window_widths") = 4.0, py::arg("min_points") = 30, R"doc(
Inflection point of a sigmoidal curve such as CN(q) (vem-void-expansion-method): x (q_i),
y (CN_i), slope with standard errors, the fit window and R^2; found=False with a message when
there is no rise or too few points.
)doc");
  m.def(
      "fit_power_law",
      [](const std::vector<double>& x, const std::vector<double>& y, double x_i, double y_i, double min_excess,
         double max_excess, int min_points) {
        PowerLawOptions o;
        o.min_excess = min_excess;
        o.max_excess = max_excess;
        o.min_points = min_points;
        const PowerLaw f = analyze::fit_power_law(x, y, x_i, y_i, o);
        py::dict d;
        d["found"] = f.found;
        d["message"] = f.message;
        d["beta"] = f.beta;
        d["beta_err"] = f.beta_err;
        d["amplitude"] = f.amplitude;
        d["amplitude_err"] = f.amplitude_err;
        d["r2"] = f.r2;
        d["points"] = f.points;
        return namespace_of(d);
      },
      py::arg("x"), py::arg("y"), py::arg("x_i"), py::arg("y_i"), py::kw_only(), py::arg("min_excess") = 0.0,
      py::arg("max_excess") = 1.0, py::arg("min_points") = 4,
      "(y - y_i) = A (x - x_i)^beta above the inflection (CN against Phi_T): beta, amplitude A, R^2.");
  m.def(
      "fit_pore_erf",
      [](const std::vector<double>& x, const std::vector<double>& p) {
        const ErfFit f = analyze::fit_pore_erf(x, p);
        py::dict d;
        d["a"] = f.a;
        d["b"] = f.b;
        d["a_err"] = f.a_err;
        d["b_err"] = f.b_err;
        d["r2"] = f.r2;
        d["points"] = f.points;
        d["converged"] = f.converged;
        return namespace_of(d);
      },
      py::arg("x"), py::arg("probability"), "Fits eq. 6 to P(x), x = r / r0.");
}

}  // namespace packlab::python
