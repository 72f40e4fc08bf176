// packlab.generate_fba: the force-biased algorithm (generate/fba.hpp), keywords named like the
// options of `packlab generate fba`; returns a types.SimpleNamespace with the packing and what
// the report holds.
#include "common.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

void bind_generate_fba(py::module_& m) {
  io::FbaOptions defaults;
  static const std::string doc = R"doc(
`packlab generate fba`: force-biased algorithm (docs/opal-build.md). Give particles (the box
follows from diameter, porosity and aspect) or box=(LX, LY, LZ) [m] (the count follows).
progress(iteration, max_overlap, outer_scale). Returns a namespace: packing, porosity, stop
("target_reached" or "max_iterations"), iterations, max_overlap, verified_max_overlap (an
independent pair search), seconds, history (dict of arrays).
)doc" + keywords_doc(io::fba_options(defaults));
  m.def(
      "generate_fba",
      [](py::object progress, double progress_interval, const py::kwargs& kwargs) {
        io::FbaOptions o;
        const io::ConfigSchema options = apply_keywords(io::fba_options(o), kwargs, "generate_fba");
        const io::FbaOptions::Setup setup = o.setup();
        options.validate();
        ProgressCallback callback(progress, progress_interval);
        generate::FbaResult r;
        {
          py::gil_scoped_release nogil;
          Random rng(o.seed);
          const std::vector<double> rho = generate::fba_class_radii(setup.count, setup.classes, rng);
          r = generate::fba_pack(setup.box, rho, o.fba, rng, o.history_every, [&](const generate::FbaStatus& s) {
            callback.tick(false, s.iteration, s.max_overlap, s.outer_scale);
          });
        }
        std::vector<long> it, pairs;
        std::vector<double> outer, inner, overlap, secs;
        for (const auto& s : r.history) {
          it.push_back(s.iteration);
          outer.push_back(s.outer_scale);
          inner.push_back(s.inner_scale);
          overlap.push_back(s.max_overlap);
          pairs.push_back(s.overlapping_pairs);
          secs.push_back(s.seconds);
        }
        py::dict history;
        history["iteration"] = to_numpy(std::move(it));
        history["outer_scale"] = to_numpy(std::move(outer));
        history["inner_scale"] = to_numpy(std::move(inner));
        history["max_overlap"] = to_numpy(std::move(overlap));
        history["overlapping_pairs"] = to_numpy(std::move(pairs));
        history["seconds"] = to_numpy(std::move(secs));
        py::dict values;
        values["porosity"] = 1.0 - r.packing.volume_fraction();
        values["packing"] = std::move(r.packing);
        values["stop"] = generate::fba_stop_name(r.status.stop);
        values["iterations"] = r.status.iteration;
        values["max_overlap"] = r.status.max_overlap;
        values["verified_max_overlap"] = r.verified_max_overlap;
        values["seconds"] = r.status.seconds;
        values["history"] = history;
        return namespace_of(values);
      },
      py::kw_only(), py::arg("progress") = py::none(), py::arg("progress_interval") = 0.5, doc.c_str());
}

}  // namespace packlab::python
