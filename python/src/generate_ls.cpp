// packlab.generate_ls: Lubachevsky-Stillinger growth of hard spheres (generate/ls.hpp), with
// keywords named like the options of `packlab generate ls`.
#include "common.hpp"
#include "generate_ls.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/ls.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

void bind_generate_ls(py::module_& m) {
  io::LsOptions defaults;
  static const std::string doc =
      "`packlab generate ls`: Lubachevsky-Stillinger growth of hard spheres from random points.\n" +
      keywords_doc(io::ls_options(defaults)) + ls_progress_doc +
      "Returns a namespace: packing, stop, volume_fraction, reduced_pressure, blocks, collisions, transfers, "
      "simulated_time, seconds, log (dict of arrays per block).";
  m.def(
      "generate_ls",
      [](py::object progress, double progress_interval, const py::kwargs& kwargs) {
        io::LsOptions o;
        const io::ConfigSchema options = apply_keywords(io::ls_options(o), kwargs, "generate_ls");
        generate::LsParams p = o.ls;
        p.target_volume_fraction = o.phi;
        p.validate();
        options.validate();
        ProgressCallback callback(progress, progress_interval);
        std::vector<double> log_phi, log_pressure, log_time;
        std::vector<long> log_block;
        Packing packing;
        generate::LsStatus status;
        {
          py::gil_scoped_release nogil;
          Random rng(o.seed);
          const generate::LsStart start =
              generate::make_ls_start(o.particles, o.classes(), o.radius, o.phi > 0 ? o.phi : 0.64, rng);
          generate::LsSimulation sim(start.box, start.points, start.unit_radius, p, rng);
          status = sim.run([&](const generate::LsStatus& s) {
            log_block.push_back(s.blocks);
            log_time.push_back(s.time);
            log_phi.push_back(s.volume_fraction);
            log_pressure.push_back(s.reduced_pressure);
            callback.tick(false, s.blocks, s.volume_fraction, s.reduced_pressure);
          });
          packing = sim.packing();
        }
        py::dict values = ls_status(status);
        values["packing"] = std::move(packing);
        py::dict log;
        log["block"] = to_numpy(std::move(log_block));
        log["time"] = to_numpy(std::move(log_time));
        log["volume_fraction"] = to_numpy(std::move(log_phi));
        log["reduced_pressure"] = to_numpy(std::move(log_pressure));
        values["log"] = log;
        return namespace_of(values);
      },
      py::kw_only(), py::arg("progress") = py::none(), py::arg("progress_interval") = 0.5, doc.c_str());
}

}  // namespace packlab::python
