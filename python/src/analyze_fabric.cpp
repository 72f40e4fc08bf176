// The fabric tensor of the contacts (analyze/fabric.hpp).
#include "common.hpp"
#include "packlab/analyze/fabric.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

void bind_analyze_fabric(py::module_& m) {
  using namespace analyze;

  py::class_<Fabric>(m, "Fabric", R"doc(
Fabric tensor of the contact normals. Fabric(contact_eps=0.01, fabric_bins=18,
fabric_without_rattlers=False, rattler_threshold=4) (the options of `packlab analyze`); compute(packing, reset=True); tensor (3 x 3, trace 1), deviator,
eigenvalues (descending), anisotropy, contacts, normal_density, bin_centers.
)doc")
      .def(py::init([](const py::kwargs& kwargs) {
        io::CoordinationSettings contacts;
        io::FabricSettings s;
        apply_keywords(io::fabric_options(contacts, s), kwargs, "Fabric").validate();
        return Fabric(contacts.contact_eps, s.fabric_bins, s.fabric_without_rattlers, contacts.rattler_threshold);
      }))
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
}

}  // namespace packlab::python
