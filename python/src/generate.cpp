// Generators with keyword arguments named like the options of `packlab generate ...`.
#include "common.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/generate/lattice.hpp"
#include "packlab/generate/random.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

void bind_generate(py::module_& m) {
  io::LatticeOptions lattice_defaults;
  static const std::string lattice_doc = R"doc(
`packlab generate lattice`: a cubic lattice (type "sc", "bcc" or "fcc") of `cells` unit cells
along x, y, z, spheres of `radius` [m] with a surface `gap` [m] between nearest neighbours
(0 = touching), in a matching periodic box.
)doc" + keywords_doc(io::lattice_options(lattice_defaults));
  m.def(
      "generate_lattice",
      [](const py::kwargs& kwargs) {
        io::LatticeOptions o;
        const io::ConfigSchema options = apply_keywords(io::lattice_options(o), kwargs, "generate_lattice");
        Packing packing = generate::make_lattice(o.params());
        options.validate();
        return packing;
      },
      lattice_doc.c_str());

  io::RandomOptions random_defaults;
  static const std::string random_doc = R"doc(
`packlab generate random`: `particles` spheres of `radius` [m] at uniform random centres in a
box of nominal volume fraction `phi` (overlaps allowed), or, with no_overlap=True, by random
sequential addition (phi < 0.36). The same seed gives the same packing as the command line.
)doc" + keywords_doc(io::random_options(random_defaults));
  m.def(
      "generate_random",
      [](const py::kwargs& kwargs) {
        io::RandomOptions o;
        const io::ConfigSchema options = apply_keywords(io::random_options(o), kwargs, "generate_random");
        const generate::RandomPackingParams p = o.params();
        Packing packing;
        {
          py::gil_scoped_release nogil;
          Random rng(o.seed);
          packing = generate::make_random_packing(p, rng);
        }
        options.validate();
        return packing;
      },
      random_doc.c_str());
  io::BondOptions bond_defaults;
  static const std::string bond_doc = R"doc(
`packlab bond`: a copy of `packing` with a bond between every pair closer than the model's
cutoff, across periodic boundaries. model "contact": d < (1 + eps)(r_i + r_j) (PFC contact
bonds, doh-elastic-properties §2.1); "elastic": d < cutoff_ratio (r_i + r_j) (elastic beam bonds
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
