// packlab.generate_scrm: LS growth alternated with shaking (generate/scrm.hpp).
#include "common.hpp"
#include "generate_ls.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/ls.hpp"
#include "packlab/generate/scrm.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

void bind_generate_scrm(py::module_& m) {
  io::ScrmOptions defaults;
  static const std::string doc =
      "`packlab generate scrm`: LS growth alternated with shaking, to the volume fraction phi.\n" +
      keywords_doc(io::scrm_options(defaults)) +
      "progress(volume_fraction, phi) instead for SCRM. Returns a namespace: packing, ls (dict), shake (dict), "
      "cycles.";
  m.def(
      "generate_scrm",
      [](py::object progress, double progress_interval, const py::kwargs& kwargs) {
        io::ScrmOptions o;
        apply_keywords(io::scrm_options(o), kwargs, "generate_scrm").validate();
        const generate::ScrmParams sp = o.params();
        ProgressCallback callback(progress, progress_interval);
        generate::ScrmResult r;
        {
          py::gil_scoped_release nogil;
          Random rng(o.seed);
          const generate::LsStart start = generate::make_ls_start(o.particles, o.classes(), o.radius, o.phi, rng);
          generate::LsSimulation sim(start.box, start.points, start.unit_radius, sp.ls, rng);
          r = run_scrm(sim, sp, rng, [&](const generate::LsStatus& ls, const generate::ShakeStats&) {
            const double volume_fraction = ls.volume_fraction;
            callback.tick(false, volume_fraction, o.phi);
          });
        }
        py::dict values;
        values["packing"] = std::move(r.packing);
        values["ls"] = ls_status(r.ls);
        values["shake"] = shake_stats(r.shake);
        values["cycles"] = r.cycles;
        return namespace_of(values);
      },
      py::kw_only(), py::arg("progress") = py::none(), py::arg("progress_interval") = 0.5, doc.c_str());
}

}  // namespace packlab::python
