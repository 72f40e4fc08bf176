// packlab.generate_bd: Brownian-dynamics coagulation with the DLVO potential
// (generate/brownian_dynamics.hpp), keywords named like the options of `packlab generate bd`;
// returns a types.SimpleNamespace with the packing and what the report holds.
#include "common.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/brownian_dynamics.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

void bind_generate_bd(py::module_& m) {
  io::BdOptions defaults;
  static const std::string doc = R"doc(
`packlab generate bd`: Brownian-dynamics coagulation of colloids with the DLVO potential
(docs/bd.md). progress(step, reduced_time, bonds). Returns a namespace: packing (with the
bonds), time_step [s], diffusion_coefficient D_0 [m^2/s], diffusion_time a^2/D_0 [s],
reduced_time (simulated time / (a^2/D_0)), bonds, clusters, largest_cluster,
mean_coordination (2 bonds / N), stop ("duration" or "stable"), barrier_kT,
secondary_minimum_kT, barrier_above_secondary_minimum_kT (has_barrier False: none),
seconds, log (dict of arrays: step, time, reduced_time, bonds, clusters, largest_cluster, msd
[m^2]).
)doc" + keywords_doc(io::bd_options(defaults));
  m.def(
      "generate_bd",
      [](py::object progress, double progress_interval, const py::kwargs& kwargs) {
        io::BdOptions o;
        const io::ConfigSchema options = apply_keywords(io::bd_options(o), kwargs, "generate_bd");
        options.validate();
        o.bd.validate();
        ProgressCallback callback(progress, progress_interval);
        generate::BdResult r;
        {
          py::gil_scoped_release nogil;
          r = generate::brownian_dynamics(o.bd, o.seed, [&](const generate::BdStatus& s) {
            callback.tick(false, s.step, s.reduced_time, s.bonds);
          });
        }
        std::vector<long> step, bonds, clusters, largest;
        std::vector<double> time, reduced, msd;
        for (const auto& s : r.log) {
          step.push_back(s.step);
          time.push_back(s.time);
          reduced.push_back(s.reduced_time);
          bonds.push_back(s.bonds);
          clusters.push_back(s.clusters);
          largest.push_back(s.largest_cluster);
          msd.push_back(s.msd);
        }
        py::dict log;
        log["step"] = to_numpy(std::move(step));
        log["time"] = to_numpy(std::move(time));
        log["reduced_time"] = to_numpy(std::move(reduced));
        log["bonds"] = to_numpy(std::move(bonds));
        log["clusters"] = to_numpy(std::move(clusters));
        log["largest_cluster"] = to_numpy(std::move(largest));
        log["msd"] = to_numpy(std::move(msd));
        const generate::DlvoProfile profile = generate::dlvo_profile(o.bd.dlvo(), o.bd.radius, o.bd.kT());
        py::dict values;
        values["packing"] = std::move(r.packing);
        values["time_step"] = r.time_step;
        values["diffusion_coefficient"] = o.bd.diffusion_coefficient();
        values["diffusion_time"] = o.bd.diffusion_time();
        values["reduced_time"] = r.status.reduced_time;
        values["bonds"] = r.status.bonds;
        values["clusters"] = r.status.clusters;
        values["largest_cluster"] = r.status.largest_cluster;
        values["mean_coordination"] = r.mean_coordination;
        values["stop"] = r.stable ? "stable" : "duration";
        values["has_barrier"] = profile.has_barrier;
        values["barrier_kT"] = profile.barrier_kT;
        values["secondary_minimum_kT"] = profile.secondary_kT;
        values["barrier_above_secondary_minimum_kT"] = profile.barrier_above_secondary_kT;
        values["seconds"] = r.status.seconds;
        values["log"] = log;
        return namespace_of(values);
      },
      py::kw_only(), py::arg("progress") = py::none(), py::arg("progress_interval") = 0.5, doc.c_str());
}

}  // namespace packlab::python
