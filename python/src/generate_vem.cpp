// packlab.generate_vem: the void expansion method (generate/vem.hpp), with the keywords of
// its option set (io::vem_options(): the keys of `packlab generate vem` with `_` for `.`).
#include "common.hpp"
#include "packlab/generate/vem.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

void bind_generate_vem(py::module_& m) {
  generate::VemParams defaults;
  static const std::string doc =
      "`packlab generate vem`: the void expansion method (docs/vem.md). " + keywords_doc(io::vem_options(defaults)) +
      R"doc(structural_material / void_material: a Material replacing the whole material (the keys
structural_material_* / void_material_* then override its fields).
progress(cycle, q, cn) (q = cn = -1 between rows). Returns a namespace: packing (structural
particles, voids removed), curve (dict of arrays: the columns of cn_curve.csv), stop, steps,
seconds, number_ratio. find_inflection(curve["q"], curve["cn"]) gives the inflection point.
)doc";
  m.def(
      "generate_vem",
      [](std::optional<dem::Material> structural_material, std::optional<dem::Material> void_material,
         py::object progress, double progress_interval, const py::kwargs& kwargs) {
        generate::VemParams p;
        if (structural_material) p.structural_material = *structural_material;
        if (void_material) p.void_material = *void_material;
        const io::ConfigSchema options = apply_keywords(io::vem_options(p), kwargs, "generate_vem");
        p.validate();
        options.validate();
        ProgressCallback callback(progress, progress_interval);
        Packing packing;
        std::vector<generate::VemRow> curve;
        std::string stop;
        long steps = 0;
        double seconds = 0.0;
        {
          py::gil_scoped_release nogil;
          generate::Vem vem(p);
          vem.on_row = [&](const generate::VemRow& row) { callback.tick(false, row.cycle, row.q, row.cn); };
          vem.on_check = [&](const dem::Diagnostics&) { callback.tick(false, vem.cycle(), -1.0, -1.0); };
          vem.run();
          packing = vem.structural_packing();
          curve = vem.curve();
          stop = generate::vem_stop_name(vem.stop_reason());
          steps = vem.total_steps();
          seconds = vem.seconds();
        }
        std::vector<long> cycle, row_steps;
        std::vector<double> q, cn, phi_total, strain, kinetic, ratio;
        std::vector<std::uint8_t> converged;
        for (const auto& r : curve) {
          cycle.push_back(r.cycle);
          q.push_back(r.q);
          cn.push_back(r.cn);
          phi_total.push_back(r.phi_total);
          strain.push_back(r.strain_energy);
          kinetic.push_back(r.kinetic_energy);
          row_steps.push_back(r.steps);
          ratio.push_back(r.unbalanced_force_ratio);
          converged.push_back(r.converged ? 1 : 0);
        }
        py::dict table;
        table["cycle"] = to_numpy(std::move(cycle));
        table["q"] = to_numpy(std::move(q));
        table["cn"] = to_numpy(std::move(cn));
        table["phi_total"] = to_numpy(std::move(phi_total));
        table["strain_energy"] = to_numpy(std::move(strain));
        table["kinetic_energy"] = to_numpy(std::move(kinetic));
        table["steps"] = to_numpy(std::move(row_steps));
        table["unbalanced_force_ratio"] = to_numpy(std::move(ratio));
        table["converged"] = to_numpy_bool(std::move(converged));
        py::dict values;
        values["packing"] = std::move(packing);
        values["curve"] = table;
        values["stop"] = stop;
        values["steps"] = steps;
        values["seconds"] = seconds;
        values["number_ratio"] = p.number_ratio();
        return namespace_of(values);
      },
      py::kw_only(), py::arg("structural_material") = py::none(), py::arg("void_material") = py::none(),
      py::arg("progress") = py::none(), py::arg("progress_interval") = 0.5, doc.c_str());
}

}  // namespace packlab::python
