// packlab.compression_test / packlab.calibrate_compress / packlab.fit_porosity_law: the uniaxial
// compression test of a bonded model (mechanics/uniaxial_compression.hpp), its calibration
// (mechanics/compression_calibration.hpp, eq. 18-20) and the porosity laws (analyze/porosity_laws.hpp) from Python.
#include "packlab/mechanics/uniaxial_compression.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <utility>

#include "columns.hpp"
#include "common.hpp"
#include "packlab/analyze/porosity_laws.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/io/mechanics_report.hpp"
#include "packlab/io/options.hpp"
#include "packlab/mechanics/compression_calibration.hpp"
#include "packlab/mechanics/opal_materials.hpp"

namespace packlab::python {

namespace {

// The set-up of a run as the command line resolves it: UniaxialCompressionSetup::finish fixes the
// automatic strain rate from the starting bond modulus.
void finish_setup(mechanics::UniaxialCompressionSetup& s, const Packing& model) {
  s.finish(model);
  s.options.validate();
}

}  // namespace

void bind_uniaxial_compression(py::module_& m) {
  using mechanics::UniaxialCompressionResult;
  py::class_<UniaxialCompressionResult>(m, "UniaxialCompressionResult",
                                        "Result of packlab.compression_test (SI units).")
      .def_readonly("youngs_modulus", &UniaxialCompressionResult::youngs_modulus,
                    "Young's modulus (max-tangent fit) [Pa]")
      .def_readonly("strength", &UniaxialCompressionResult::strength, "Peak stress [Pa]")
      .def_readonly("strain_at_peak", &UniaxialCompressionResult::strain_at_peak)
      .def_readonly("broken_bonds", &UniaxialCompressionResult::broken_bonds)
      .def_readonly("height", &UniaxialCompressionResult::height, "H0 [m]")
      .def_readonly("area", &UniaxialCompressionResult::area, "Cross-section [m^2]")
      .def_readonly("time_step", &UniaxialCompressionResult::time_step, "[s]")
      .def_readonly("steps", &UniaxialCompressionResult::steps)
      .def_readonly("bonds", &UniaxialCompressionResult::bonds)
      .def_readonly("fixed_particles", &UniaxialCompressionResult::fixed_particles)
      .def_readonly("max_kinetic_ratio", &UniaxialCompressionResult::max_kinetic_ratio)
      .def_readonly("rate_switch_strain", &UniaxialCompressionResult::rate_switch_strain,
                    "Dynamic solver, elastic_speedup > 1: strain where the plate slowed to strain_rate (NaN: never)")
      .def_readonly("rolled_back_steps", &UniaxialCompressionResult::rolled_back_steps,
                    "Dynamic solver, elastic_speedup > 1: fast steps discarded at the first break")
      .def_readonly("effective_speedup", &UniaxialCompressionResult::effective_speedup,
                    "Dynamic solver: the speed-up run (elastic_speedup rounded to keep the points' spacing; 1 = none)")
      .def_readonly("stop_reason", &UniaxialCompressionResult::stop_reason)
      .def_readonly("solver", &UniaxialCompressionResult::solver, "dynamic or static")
      .def_readonly("poisson_ratio", &UniaxialCompressionResult::poisson_ratio,
                    "Static solver, open sides: -lateral / axial strain (NaN otherwise)")
      .def_readonly("solves", &UniaxialCompressionResult::solves, "Static solver: linear solves")
      .def_readonly("model", &UniaxialCompressionResult::model, "The model after the test (bond states)")
      .def_readonly("seconds", &UniaxialCompressionResult::seconds)
      .def_property_readonly(
          "fit_window",
          [](const UniaxialCompressionResult& r) {
            return std::make_pair(r.modulus.strain_begin, r.modulus.strain_end);
          },
          "Strain range of the modulus fit")
      .def_property_readonly(
          "curve", [](const UniaxialCompressionResult& r) { return columns_dict(mechanics::curve_columns(r.curve)); },
          "Columns of curve.csv as a dict of arrays: step, time, displacement, strain, force, stress, ...")
      .def_property_readonly(
          "breaks",
          [](const UniaxialCompressionResult& r) {
            std::vector<double> time;
            std::vector<Vec3> position;
            std::vector<long> bond;
            for (const auto& b : r.breaks) {
              time.push_back(b.time);
              position.push_back(b.position);
              bond.push_back(static_cast<long>(b.bond));
            }
            py::dict d;
            d["bond"] = to_numpy(std::move(bond));
            d["time"] = to_numpy(std::move(time));
            d["position"] = to_numpy(std::move(position));
            d["strain"] = to_numpy(std::vector<double>(r.break_strain));
            return d;
          },
          "Bond failures: bond index into model.bonds, time [s], position (midpoint) [m], strain at the break")
      .def_property_readonly(
          "snapshots",
          [](const UniaxialCompressionResult& r) {
            py::list out;
            for (const auto& s : r.snapshots) {
              py::dict d;
              if (s.by_stress())
                d["requested_stress"] = s.requested_stress;
              else
                d["requested_strain"] = s.requested_strain;
              d["strain"] = s.strain;
              d["stress"] = s.stress;
              d["bond_strain"] = to_numpy(std::vector<double>(s.bond_strain));
              std::vector<double> flat;
              for (const auto& a : s.particle_stress) flat.insert(flat.end(), a.begin(), a.end());
              py::array stress = to_numpy(std::move(flat));
              d["particle_stress"] =
                  stress.attr("reshape")(py::make_tuple(static_cast<py::ssize_t>(s.particle_stress.size()), 3, 3));
              py::list types;
              for (const auto& t : analyze::stress_by_type(r.model, s.particle_stress))
                types.append(py::dict(py::arg("type") = t.type, py::arg("particles") = t.particles,
                                      py::arg("mean") = t.mean, py::arg("sd") = t.sd));
              d["stress_by_type"] = types;
              out.append(d);
            }
            return out;
          },
          "Snapshots at snapshot_strains and snapshot_stresses (in the order taken): requested_strain or "
          "requested_stress, strain, stress, bond_strain, particle_stress (N x 3 x 3), stress_by_type")
      .def("__repr__", [](const UniaxialCompressionResult& r) {
        return fmt::format("<UniaxialCompressionResult: E = {:.4g} Pa, strength = {:.4g} Pa, {} broken bonds>",
                           r.youngs_modulus, r.strength, r.broken_bonds);
      });

  mechanics::UniaxialCompressionSetup test_defaults;
  static const std::string test_doc = R"doc(
`packlab test compress` from Python: uniaxial compression of a bonded model (bonds in
model.bonds, e.g. from packlab.add_bonds or a .vtu of `packlab bond` / `packlab build opal`) by
a plate moving down at strain_rate [1/s] (0 = automatic: quasi_static strain per elastic-wave
transit). Silica = bond material 0 (and particle types structural/substrate), titania = bond
material 1 (coating particles). Returns a UniaxialCompressionResult (youngs_modulus, strength [Pa],
curve, snapshots, breaks, model). The GIL is released while it runs; progress(strain, stress)
is called at most every progress_interval seconds.

)doc" + keywords_doc(io::compression_test_options(test_defaults));
  m.def(
      "compression_test",
      [](const Packing& model, py::object progress, double progress_interval, const py::kwargs& kwargs) {
        mechanics::UniaxialCompressionSetup s;
        apply_keywords(io::compression_test_options(s), kwargs, "compression_test");
        finish_setup(s, model);
        ProgressCallback callback(progress, progress_interval);
        if (!progress.is_none())
          s.options.on_point = [&](const mechanics::UniaxialCompressionPoint& p) {
            callback.tick(false, p.strain, p.stress);
          };
        py::gil_scoped_release nogil;
        return mechanics::run_uniaxial_compression(model, s.options);
      },
      py::arg("model"), py::kw_only(), py::arg("progress") = py::none(), py::arg("progress_interval") = 0.5,
      test_doc.c_str());

  io::CompressionCalibrationRun calibration_defaults;
  static const std::string calibrate_doc = R"doc(
`packlab calibrate compress` from Python (bpm-inverse-opals eq. 18-20). With the targets:
Newton steps on the silica bond Young's modulus E_b and strength sigma_max (= tau_max), starting
from bond_youngs_modulus and bond_strength, with finite-difference derivatives (relative_step),
until the compression test gives target_youngs_modulus and target_strength [Pa] within
tolerance (relative); the paper's diagonal scheme unless full_jacobian. With bulk_factor=True
(a pore-free sample): one test, K_E = E_macro / E_b. The other keywords are those of
packlab.compression_test (the automatic strain rate is fixed by the starting E_b, as on the
command line). Returns a dict: mode, bond_youngs_modulus, bond_strength, youngs_modulus,
strength, final (the UniaxialCompressionResult of the result's parameters); calibration:
converged, reason, iterations, simulations, history {bond_youngs_modulus, bond_strength,
youngs_modulus, strength, finite_difference, evaluation} (every simulation in order); bulk factor:
bulk_factor, strength_ratio (E_macro / strength), strength_factor (strength / sigma_max). A
calibration that does not converge returns converged=False. progress(run, E_b, sigma_max, E,
strength) is called after each simulation.

)doc" + keywords_doc(io::compression_calibration_options(calibration_defaults));
  m.def(
      "calibrate_compress",
      [](const Packing& model, py::object progress, const py::kwargs& kwargs) {
        io::CompressionCalibrationRun run;
        apply_keywords(io::compression_calibration_options(run), kwargs, "calibrate_compress").validate();
        mechanics::UniaxialCompressionSetup& s = run.setup;
        finish_setup(s, model);
        if (run.bulk_factor) {
          mechanics::BulkFactorResult b;
          {
            py::gil_scoped_release nogil;
            b = mechanics::compression_bulk_factor(model, s);
          }
          py::dict d = json_to_python(io::bulk_factor_summary(b, s));
          d["final"] = py::cast(std::move(b.run));
          return d;
        }
        run.calibration.diagonal = !run.full_jacobian;
        auto on_run = [&](int simulation, const std::vector<double>& p, const mechanics::UniaxialCompressionResult& r) {
          if (progress.is_none()) return;
          py::gil_scoped_acquire gil;
          progress(simulation, p[0], p[1], r.youngs_modulus, r.strength);
        };
        mechanics::CompressionCalibrationResult result;
        {
          py::gil_scoped_release nogil;
          result = mechanics::calibrate_compression(model, s, run.target_youngs_modulus, run.target_strength,
                                                    run.calibration, on_run);
        }
        py::dict d = json_to_python(io::compression_calibration_summary(result, run.calibration));
        d["history"] = columns_dict(mechanics::calibration_history_columns(result.calibration));
        d["final"] = result.has_final ? py::cast(std::move(result.final)) : py::object(py::none());
        return d;
      },
      py::arg("model"), py::kw_only(), py::arg("progress") = py::none(), calibrate_doc.c_str());

  using analyze::PorosityFit;
  py::class_<PorosityFit>(m, "PorosityFit", "Fit of a porosity law (eq. 22-26).")
      .def_property_readonly("law", [](const PorosityFit& f) { return analyze::porosity_law_name(f.law); })
      .def_readonly("e0", &PorosityFit::e0)
      .def_readonly("e0_err", &PorosityFit::e0_err)
      .def_readonly("exponent", &PorosityFit::exponent, "b (exponential) or m (power)")
      .def_readonly("exponent_err", &PorosityFit::exponent_err)
      .def_readonly("rss", &PorosityFit::rss)
      .def_readonly("rms_relative", &PorosityFit::rms_relative)
      .def_readonly("r2", &PorosityFit::r2)
      .def("__call__", &PorosityFit::model, py::arg("porosity"))
      .def("__repr__", [](const PorosityFit& f) {
        return fmt::format("<PorosityFit {}: E0 = {:.4g}, exponent = {:.4g} +- {:.2g}, rms rel. {:.3g}>",
                           analyze::porosity_law_name(f.law), f.e0, f.exponent, f.exponent_err, f.rms_relative);
      });
  m.def(
      "fit_porosity_law",
      [](const std::string& law, py::object porosity, py::object value, double fixed_e0) {
        return analyze::fit_porosity_law(analyze::porosity_law_from_name(law), from_numpy<double>(porosity, "porosity"),
                                         from_numpy<double>(value, "value"), fixed_e0);
      },
      py::arg("law"), py::arg("porosity"), py::arg("value"), py::arg("fixed_e0") = 0.0,
      "Fits 'exponential' E0 exp(-b eps) (eq. 22, 26) or 'power' E0 (1 - eps)^m (eq. 23); fixed_e0 > 0 holds E0.");
}

}  // namespace packlab::python
