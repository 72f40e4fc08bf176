// packlab.shake: Monte-Carlo shaking of a packing without overlaps (generate/shake.hpp).
#include "common.hpp"
#include "generate_ls.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/shake.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

void bind_generate_shake(py::module_& m) {
  io::ShakeOptions defaults;
  static const std::string doc = R"doc(
`packlab shake`: Monte-Carlo shaking of a packing without overlaps (a copy; the input is
unchanged). progress(done, total) after sweeps. Returns a namespace: packing, sweeps, visits,
trials, moves, mean_step, seconds, window.
)doc" + keywords_doc(io::shake_options(defaults));
  m.def(
      "shake",
      [](const Packing& packing, py::object progress, double progress_interval, const py::kwargs& kwargs) {
        io::ShakeOptions o;
        apply_keywords(io::shake_options(o), kwargs, "shake").validate();
        ProgressCallback callback(progress, progress_interval);
        Packing out = packing;
        generate::ShakeStats stats;
        {
          py::gil_scoped_release nogil;
          Random rng(o.seed);
          generate::Shaker shaker(out, o.shake);
          shaker.sweeps(o.sweeps, rng, [&](const generate::ShakeStats& s) {
            const long done = s.sweeps;
            callback.tick(false, done, o.sweeps);
          });
          stats = shaker.stats();
        }
        py::dict values = shake_stats(stats);
        values["packing"] = std::move(out);
        return namespace_of(values);
      },
      py::arg("packing"), py::kw_only(), py::arg("progress") = py::none(), py::arg("progress_interval") = 0.5,
      doc.c_str());
}

}  // namespace packlab::python
