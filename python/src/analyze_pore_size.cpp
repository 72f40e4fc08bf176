// The pore-size distribution by the exclusion probability and its erf fit, the degree of
// heterogeneity (analyze/pore_size.hpp).
#include "common.hpp"
#include "packlab/analyze/pore_size.hpp"
#include "packlab/core/random.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

void bind_analyze_pore_size(py::module_& m) {
  using namespace analyze;

  py::class_<PoreSize>(m, "PoreSize", R"doc(
Pore-size distribution P(r_P > r) by the exclusion probability (doh-elastic-properties eq. 6).
PoreSize(points=0, band=0.005, confidence=0.95, pore_definition="pore_space", wall_margin=-1,
threads=0): points counted per packing (0 = from the confidence band), pore_definition
"pore_space" or "all_points", wall_margin [m] along open axes (< 0 = one mean diameter).
compute(packing, seed=1, reset=True); curve() -> dict r [m], probability, std_error,
band_low, band_high; fit_doh() -> the erf fit giving the degree of heterogeneity (a, b).
)doc")
      .def(py::init([](const py::kwargs& kwargs) {
        io::PoreSizeSettings s;
        apply_keywords(io::pore_size_options(s), kwargs, "PoreSize").validate();
        return PoreSize(s.params());
      }))
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
      .def(
          "distances", [](const PoreSize& s, int frame) { return to_numpy(std::vector<double>(s.distances(frame))); },
          py::arg("frame") = -1, "Distance of each counted point to the nearest particle surface [m].")
      .def_property_readonly("frames", &PoreSize::frames)
      .def("porosity", &PoreSize::porosity, py::arg("frame") = -1)
      .def("porosity_std_error", &PoreSize::porosity_std_error, py::arg("frame") = -1)
      .def("counted_points", &PoreSize::counted_points, py::arg("frame") = -1)
      .def("mean_radius", &PoreSize::mean_radius, py::arg("frame") = -1)
      .def(
          "fit_doh",
          [](const PoreSize& s, int frame, const py::kwargs& kwargs) {
            io::DohFitSettings settings;
            apply_keywords(io::doh_fit_options(settings), kwargs, "fit_doh").validate();
            const DohFitOptions o = settings.options();
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
          py::kw_only(), py::arg("frame") = -1,
          "Error-function fit of eq. 6: a (degree of heterogeneity) and b in units of r0 [m] (0 = mean radius). "
          "Keywords r0, fit_range (XMIN, XMAX of r/r0), fit_p_min, fit_grid as the options of `packlab analyze`.");
  m.def("pore_erf_model", &pore_erf_model, py::arg("x"), py::arg("a"), py::arg("b"), "The eq. 6 model P(x; a, b).");
}

}  // namespace packlab::python
