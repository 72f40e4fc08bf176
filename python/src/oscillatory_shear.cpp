// packlab.bond, packlab.shear_test, packlab.calibrate_shear: bonded models and the
// oscillatory shear test of doh-elastic-properties §2.4 with keywords named like the options of
// `packlab bond` and `packlab test shear`. The runs release the GIL; the optional progress
// callback is called (throttled) with the GIL held.
#include <fmt/format.h>

#include <cmath>

#include "columns.hpp"
#include "common.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/io/mechanics_report.hpp"
#include "packlab/io/options.hpp"
#include "packlab/mechanics/oscillatory_shear.hpp"
#include "packlab/mechanics/shear_calibration.hpp"

namespace packlab::python {

namespace {

using mechanics::OscillatoryShearOptions;

// The command's report block, with each orientation's samples and cycles as arrays and the
// relaxed structure.
py::dict result_dict(const mechanics::OscillatoryShearResult& r, int regions) {
  py::dict out = json_to_python(io::oscillatory_shear_summary(r));
  py::list per = out["storage_modulus"]["per_orientation"];
  for (std::size_t k = 0; k < r.runs.size(); ++k) {
    py::dict d = per[k];
    d["samples"] = columns_dict(mechanics::shear_sample_columns(r.runs[k].samples, regions));
    d["cycles"] = columns_dict(mechanics::shear_cycle_columns(r.runs[k].cycles));
  }
  out["packing"] = r.relaxed_packing;
  return out;
}

}  // namespace

void bind_oscillatory_shear(py::module_& m) {
  io::ShearTestRun test_defaults;
  static const std::string shear_doc = R"doc(
`packlab test shear` from Python: the oscillatory shear test of a bonded periodic packing
(doh-elastic-properties §2.4). Returns the results of the command's report.json as a dict:
storage_modulus {mean, std, unit, per_orientation: [{orientation, storage_modulus, complex_modulus,
phase_angle, plate_storage_modulus, broken_bonds, ..., samples: {cycle, step, time, phase, strain,
stress, plate_stress, region_k, ...}, cycles: {cycle, strain_amplitude, ..., storage_modulus, ...}}]}
[Pa], phase_angle [rad], bonds, relaxation, seconds; and packing (the relaxed structure). The keywords are the options of the
command; stiffnesses [N/m] are particle stiffnesses under stiffness_rule "particle" (contacts and
bonds act with k/2). progress(stage, done, total) is called with the GIL held at most every
progress_interval seconds.

)doc" + keywords_doc(io::shear_test_options(test_defaults));
  m.def(
      "shear_test",
      [](const Packing& packing, py::object progress, double progress_interval, const py::kwargs& kwargs) {
        io::ShearTestRun run;
        apply_keywords(io::shear_test_options(run), kwargs, "shear_test");
        OscillatoryShearOptions o = run.test;
        mechanics::validate(o);
        ProgressCallback callback(progress, progress_interval);
        o.progress = [&](const std::string& stage, long done, long total) { callback.tick(false, stage, done, total); };
        mechanics::OscillatoryShearResult r;
        {
          py::gil_scoped_release nogil;
          r = mechanics::run_oscillatory_shear(packing, o);
        }
        return result_dict(r, o.regions);
      },
      py::arg("packing"), py::kw_only(), py::arg("progress") = py::none(), py::arg("progress_interval") = 0.5,
      shear_doc.c_str());

  io::ShearCalibrationRun calibration_defaults;
  static const std::string calibrate_doc = R"doc(
`packlab calibrate shear` from Python: the particle normal stiffness k_n [N/m] (k_s following at the
ratio shear_stiffness / normal_stiffness) for which the mean storage modulus equals
target_storage_modulus [Pa]; Newton with a finite-difference derivative. Returns a dict
(normal_stiffness, shear_stiffness, storage_modulus, converged, iterations, evaluations, reason,
tried_*).

)doc" + keywords_doc(io::shear_calibration_options(calibration_defaults));
  m.def(
      "calibrate_shear",
      [](const Packing& packing, const py::kwargs& kwargs) {
        io::ShearCalibrationRun run;
        apply_keywords(io::shear_calibration_options(run), kwargs, "calibrate_shear").validate();
        mechanics::ShearCalibrationResult r;
        {
          py::gil_scoped_release nogil;
          r = mechanics::calibrate_normal_stiffness(packing, run.target_storage_modulus, run.test, run.tolerance,
                                                    static_cast<int>(run.max_iterations));
        }
        py::dict d;
        d["normal_stiffness"] = r.normal_stiffness;
        d["shear_stiffness"] = r.shear_stiffness;
        d["storage_modulus"] = r.storage_modulus;
        d["converged"] = r.converged;
        d["iterations"] = r.iterations;
        d["evaluations"] = r.evaluations;
        d["reason"] = r.reason;
        d["tried_normal_stiffness"] = to_numpy(std::vector<double>(r.tried_normal_stiffness));
        d["tried_storage_modulus"] = to_numpy(std::vector<double>(r.tried_storage_modulus));
        return d;
      },
      py::arg("packing"), calibrate_doc.c_str());
}

}  // namespace packlab::python
