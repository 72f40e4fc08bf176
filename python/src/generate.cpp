// Generators with keyword arguments named like the options of `packlab generate ...`.
#include "common.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/generate/lattice.hpp"
#include "packlab/generate/random.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

void bind_generate(py::module_& m) {
  m.def(
      "generate_lattice",
      [](const std::string& type, std::array<int, 3> cells, double radius, double gap) {
        generate::LatticeParams p;
        p.type = generate::lattice_type_from_name(type);
        p.cells = cells;
        p.radius = radius;
        p.gap = gap;
        return generate::make_lattice(p);
      },
      py::kw_only(), py::arg("type") = "fcc", py::arg("cells") = std::array<int, 3>{4, 4, 4},
      py::arg("radius") = 0.5, py::arg("gap") = 0.0, R"doc(
`packlab generate lattice`: a cubic lattice (type "sc", "bcc" or "fcc") of `cells` unit cells
along x, y, z, spheres of `radius` [m] with a surface `gap` [m] between nearest neighbours
(0 = touching), in a matching periodic box.
)doc");

  m.def(
      "generate_random",
      [](long particles, double radius, double phi, bool no_overlap, std::array<bool, 3> periodic,
         std::array<double, 3> aspect, std::uint64_t seed) {
        generate::RandomPackingParams p;
        p.particles = particles;
        p.radius = radius;
        p.volume_fraction = phi;
        p.allow_overlap = !no_overlap;
        p.periodic = periodic;
        p.aspect = aspect;
        Random rng(seed);
        py::gil_scoped_release nogil;
        return generate::make_random_packing(p, rng);
      },
      py::kw_only(), py::arg("particles") = 1000, py::arg("radius") = 0.5, py::arg("phi") = 0.5,
      py::arg("no_overlap") = false, py::arg("periodic") = std::array<bool, 3>{true, true, true},
      py::arg("aspect") = std::array<double, 3>{1, 1, 1}, py::arg("seed") = 1, R"doc(
`packlab generate random`: `particles` spheres of `radius` [m] at uniform random centres in a
box of nominal volume fraction `phi` (overlaps allowed), or, with no_overlap=True, by random
sequential addition (phi < 0.36). periodic: per axis; aspect: box edge ratios; seed: the
random seed (the same seed gives the same packing as the command line).
)doc");
  io::BondOptions bond_defaults;
  static const std::string bond_doc = R"doc(
`packlab bond`: a copy of `packing` with a bond between every pair closer than the model's
cutoff, across periodic boundaries. model "contact": d < (1 + eps)(r_i + r_j) (PFC contact
bonds, doh-elastic-properties §2.1); "beam": d < cutoff_ratio (r_i + r_j) (elastic beam bonds
within 1.75 d, bpm-inverse-opals §2.1). Bonds are saved in .vtu files.
)doc" + keywords_doc(io::bond_options(bond_defaults));
  m.def(
      "bond",
      [](const Packing& packing, const py::kwargs& kwargs) {
        io::BondOptions o;
        apply_keywords(io::bond_options(o), kwargs, "bond").validate();
        generate::BondingOptions bonding;
        bonding.cutoff_ratio = generate::bonding_cutoff_ratio(o.model, o.eps, o.cutoff_ratio);
        bonding.threads = o.threads;
        Packing bonded = packing;
        py::gil_scoped_release nogil;
        generate::add_bonds(bonded, bonding);
        return bonded;
      },
      py::arg("packing"), bond_doc.c_str());
}

}  // namespace packlab::python
