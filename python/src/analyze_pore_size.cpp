// The pore-size distribution by the exclusion probability and its erf fit, the degree of
// heterogeneity (analyze/pore_size.hpp).
#include "common.hpp"
#include "packlab/analyze/pore_size.hpp"
#include "packlab/core/random.hpp"

namespace packlab::python {

void bind_analyze_pore_size(py::module_& m) {
  using namespace analyze;

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
}

}  // namespace packlab::python
