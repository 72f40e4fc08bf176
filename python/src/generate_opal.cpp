// packlab.build_opal: the inverse-opal builder (generate/opal.hpp), keywords named like the
// options of `packlab build opal`; returns a types.SimpleNamespace with the model and what the
// report holds.
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "common.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/generate/opal.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

void bind_generate_opal(py::module_& m) {
  io::OpalBuildOptions defaults;
  static const std::string doc = R"doc(
`packlab build opal`: inverse-opal bonded-particle model (docs/opal-build.md). pores: "fcc",
"random" or "list" (pore_centres N x 3 and pore_radii N [m], Python only). Returns a
namespace: packing (types 0 silica, 3 titania, 4 substrate; fixed; bonds with material 0
silica, 1 titania, 2 substrate), pore_centres, pore_radii and the report's figures (particles,
bonds, mean_coordination, porosity, density, ...).
)doc" + keywords_doc(io::opal_build_options(defaults)) +
      "  pore_centres, pore_radii: the pores when pores = \"list\"\n";
  m.def(
      "build_opal",
      [](const Packing& packing, py::object pore_centres, py::object pore_radii, py::kwargs kwargs) {
        io::OpalBuildOptions options;
        const std::string pores =
            kwargs.contains("pores") ? py::str(kwargs["pores"]).cast<std::string>() : options.pores;
        if (pores == "list") kwargs.attr("pop")("pores");
        const io::ConfigSchema schema = apply_keywords(io::opal_build_options(options), kwargs, "build_opal");
        generate::OpalOptions o = options.opal;
        if (pores == "list") {
          require(packing.size() >= 1, "particles", 0, ">= 1 in the input packing");
          if (pore_centres.is_none() || pore_radii.is_none())
            fail_input("pores = list: give pore_centres (N x 3) and pore_radii (N)");
          o.pores.centre = vec3s_from_numpy(pore_centres, "pore_centres");
          o.pores.radius =
              from_numpy<double>(pore_radii, "pore_radii", static_cast<py::ssize_t>(o.pores.centre.size()));
        } else {
          o = options.resolve(packing);
        }
        schema.validate();
        generate::OpalSummary s;
        Packing model;
        generate::PoreSet set;
        {
          py::gil_scoped_release nogil;
          model = generate::build_opal(packing, o, &s);
          set = generate::opal_pores(packing, o);
        }
        py::dict values;
        values["packing"] = std::move(model);
        values["pore_centres"] = py::array_t<double>(
            {static_cast<py::ssize_t>(set.size()), py::ssize_t{3}},
            reinterpret_cast<const double*>(set.centre.data()));
        values["pore_radii"] = to_numpy(std::move(set.radius));
        values["input_particles"] = s.input_particles;
        values["particles"] = s.particles;
        values["silica_particles"] = s.structural;
        values["titania_particles"] = s.coating;
        values["substrate_particles"] = s.substrate;
        values["removed_particles"] = s.removed;
        values["coating_dropped_at_openings"] = s.coating_openings;
        values["pores"] = s.pores;
        values["bonds"] = s.bonds;
        values["bonds_by_material"] = s.bonds_by_material;
        values["periodic_bonds"] = s.periodic_bonds;
        values["mean_coordination"] = s.mean_coordination;
        values["porosity"] = s.porosity;
        values["particle_porosity"] = s.particle_porosity;
        values["density"] = s.density;
        values["substrate_top"] = s.substrate_top;
        values["bond_radius_ratio"] = s.bond_radius_ratio;
        values["lattice_commensurate"] = s.lattice_commensurate;
        values["seconds"] = s.seconds;
        return namespace_of(values);
      },
      py::arg("packing"), py::kw_only(), py::arg("pore_centres") = py::none(), py::arg("pore_radii") = py::none(),
      doc.c_str());
}

}  // namespace packlab::python
