// Analyses like freud's: parameters in the constructor, compute(packing), results as arrays.
#include "common.hpp"
#include "packlab/analyze/coordination.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

void bind_analyze(py::module_& m) {
  using analyze::Coordination;
  m.def(
      "find_contacts",
      [](const Packing& packing, double contact_eps, int threads) {
        analyze::ContactList c;
        {
          py::gil_scoped_release nogil;
          c = analyze::find_contacts(packing, contact_eps, threads);
        }
        py::dict out;
        out["i"] = to_numpy(std::move(c.i));
        out["j"] = to_numpy(std::move(c.j));
        out["branch"] = to_numpy(std::move(c.branch));
        return out;
      },
      py::arg("packing"), py::kw_only(), py::arg("contact_eps") = 0.01, py::arg("threads") = 1, R"doc(
Pairs with centre distance below (1 + contact_eps)(r_i + r_j), periodic images included, each
once (i <= j; i == j is a periodic self image): dict of i, j and branch (M x 3, r_j + shift - r_i [m]).
)doc");

  py::class_<Coordination>(m, "Coordination", R"doc(
Coordination numbers (`packlab info`, `packlab analyze`): contact when the centre distance is
below (1 + contact_eps)(r_i + r_j); rattlers have fewer than rattler_threshold contacts,
removed repeatedly (rattler_rule "iterative", the k-core) or flagged once ("single_pass").
compute(packing, reset=True) returns self; reset=False accumulates realizations. Reading a
result before compute raises. Per-particle arrays describe the last packing.
)doc")
      .def(py::init([](const py::kwargs& kwargs) {
        io::CoordinationSettings s;
        apply_keywords(io::coordination_options(s), kwargs, "Coordination").validate();
        return Coordination(s.contact_eps, s.rattler_threshold, analyze::rattler_rule_from_name(s.rattler_rule));
      }))
      .def(
          "compute",
          [](py::object self, const Packing& packing, bool reset) {
            auto& c = self.cast<Coordination&>();
            {
              py::gil_scoped_release nogil;
              c.compute(packing, reset);
            }
            return self;
          },
          py::arg("packing"), py::arg("reset") = true)
      .def_property_readonly(
          "counts",
          [](py::object self) {
            auto& v = const_cast<std::vector<int>&>(self.cast<Coordination&>().counts());
            return view(v, self, false);
          },
          "Contacts per particle (read-only view).")
      .def_property_readonly(
          "rattlers",
          [](py::object self) {
            auto& v = const_cast<std::vector<std::uint8_t>&>(self.cast<Coordination&>().rattlers());
            return bool_view(v, self, false);
          },
          "True for rattlers (read-only view).")
      .def_property_readonly("contacts", &Coordination::contacts, "Number of contacts (pairs), last packing.")
      .def_property_readonly("mean", &Coordination::mean, "Mean contacts per particle.")
      .def_property_readonly("mean_without_rattlers", &Coordination::mean_without_rattlers,
                             "Mean contacts among non-rattlers per non-rattler.")
      .def_property_readonly("rattler_count", &Coordination::rattler_count)
      .def_property_readonly("particle_count", &Coordination::particle_count)
      .def_property_readonly("frames", &Coordination::frames, "Packings accumulated since the last reset.")
      .def_property_readonly(
          "distribution",
          [](const Coordination& c) {
            auto d = c.distribution();
            return to_numpy(std::move(d));
          },
          "distribution[k] = number of particles with k contacts.")
      .def_property_readonly("types", &Coordination::types, "Particle types present (ascending).")
      .def_property_readonly("mean_by_type", &Coordination::mean_by_type, "Mean contacts per particle of each type.")
      .def_property_readonly("particles_by_type", &Coordination::particles_by_type)
      .def_property_readonly("rattlers_by_type", &Coordination::rattlers_by_type)
      .def_property_readonly("between_types", &Coordination::between_types,
                             "[a][b]: mean contacts with type types[b] per particle of type types[a].")
      .def_property_readonly("contact_eps", &Coordination::contact_eps)
      .def_property_readonly("rattler_threshold", &Coordination::rattler_threshold);
}

}  // namespace packlab::python
