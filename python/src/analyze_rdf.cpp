// packlab.Rdf and the analytic reference RDFs (analyze/rdf.hpp, analyze/reference_rdf.hpp).
#include "common.hpp"
#include "packlab/analyze/rdf.hpp"
#include "packlab/analyze/reference_rdf.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

void bind_analyze_rdf(py::module_& m) {
  using namespace analyze;

  py::class_<Rdf>(m, "Rdf", R"doc(
Radial distribution function g(r) and partial g_km via the K-function (`packlab analyze rdf`).
Rdf(dr=0.01, r_max=8.0, window_radius=2.5, edge="auto", threads=0): dr and r_max in units
of the reference radius a (the largest class radius); edge: "automatic" (toroidal when every
axis is periodic), "toroidal", "ripley" or "minus_sampling". compute(packing) forgets earlier
realizations, accumulate(packing) adds one. Class k = -1 means all particles.
)doc")
      .def(py::init([](const py::kwargs& kwargs) {
        io::RdfSettings s;
        const io::ConfigSchema schema = apply_keywords(io::rdf_options(s), kwargs, "Rdf");
        schema.validate();
        return Rdf(s.validated());
      }))
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
      .def_property_readonly(
          "r", [](const Rdf& r) { return to_numpy(r.reduced_r()); }, "Bin centres r/a.")
      .def(
          "g", [](const Rdf& r, int k, int l) { return to_numpy(r.g(k, l)); }, py::arg("k") = -1, py::arg("m") = -1,
          "g(r) (partial g_km for classes k, m).")
      .def(
          "k_function", [](const Rdf& r, int k, int l) { return to_numpy(r.k_function(k, l)); }, py::arg("k") = -1,
          py::arg("m") = -1)
      .def(
          "shell_count", [](const Rdf& r, int k, int l) { return to_numpy(r.shell_count(k, l)); }, py::arg("k") = -1,
          py::arg("m") = -1)
      .def("contact_value", &Rdf::contact_value, py::arg("k") = -1, py::arg("m") = -1, "g at contact, g(2a+).")
      .def("peaks", &Rdf::peaks, py::arg("k") = -1, py::arg("m") = -1, py::arg("count") = 4,
           "Positions r/a of the first peaks.")
      .def(
          "window_histogram", [](const Rdf& r, int k) { return to_numpy(r.window_histogram(k)); }, py::arg("k") = -1,
          "p(n): fraction of windows holding n centres.")
      .def("windows", &Rdf::windows, py::arg("k") = -1);

  auto ref = m.def_submodule("reference", "Analytic reference RDFs (well-stirred, Willis, Percus-Yevick).");
  ref.def("well_stirred", &reference::well_stirred, py::arg("r"), py::arg("a"));
  ref.def("willis", &reference::willis, py::arg("r"), py::arg("a"), py::arg("c"), py::arg("use_original") = false,
          "Willis' g(r) for spheres of radius a at volume fraction c.");
  ref.def("percus_yevick_contact", &reference::percus_yevick_contact, py::arg("c"), "g(2a+) of Percus-Yevick.");
  ref.def("percus_yevick_contact_mixture", &reference::percus_yevick_contact_mixture, py::arg("radius"),
          py::arg("volume_fraction"));
  ref.def("percus_yevick", &reference::percus_yevick, py::arg("r_over_a"), py::arg("c"),
          "The full Percus-Yevick g at R = r/a (contact at R = 2) of hard spheres at volume fraction c "
          "(Wertheim's solution, Ornstein-Zernike in Fourier space, one numerical sine transform).");
}

}  // namespace packlab::python
