// Fits: the CN(q) inflection point, the power law of the CN excess and the porosity laws
// (analyze/inflection.hpp, power_law.hpp, fits.hpp).
#include "common.hpp"
#include "packlab/analyze/fits.hpp"
#include "packlab/analyze/inflection.hpp"
#include "packlab/analyze/power_law.hpp"

namespace packlab::python {

void bind_analyze_fits(py::module_& m) {
  using namespace analyze;

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
