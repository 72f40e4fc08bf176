// packlab.compress / packlab.calibrate_compress / packlab.fit_porosity_law: the uniaxial
// compression test of a bonded model (mechanics/uniaxial_compression.hpp), its calibration
// (mechanics/compression_calibration.hpp, eq. 18-20) and the porosity laws (analyze/porosity_laws.hpp) from Python.
#include <fmt/format.h>

#include <cstdint>
#include <utility>

#include "columns.hpp"
#include "common.hpp"
#include "packlab/analyze/porosity_laws.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/mechanics/compression_calibration.hpp"
#include "packlab/mechanics/opal_materials.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"

namespace packlab::python {

namespace {

// The keywords shared by packlab.compress and packlab.calibrate_compress (the flags of
// `packlab test compress`), as the command line resolves them: UniaxialCompressionSetup::finish fixes
// the automatic strain rate from the starting bond modulus.
mechanics::UniaxialCompressionSetup make_setup(const Packing& model, double bond_youngs_modulus, double bond_poisson,
                                       double bond_strength, double density, double titania_youngs_modulus,
                                       double titania_poisson, double titania_strength, double strain_rate,
                                       double quasi_static, double max_strain, double stop_drop,
                                       const std::string& sides, double substrate_layers, double damping,
                                       double time_step, long samples, std::vector<double> snapshot_strains,
                                       int threads) {
  mechanics::UniaxialCompressionSetup s;
  s.materials.silica_youngs_modulus = bond_youngs_modulus;
  s.materials.silica_poisson_ratio = bond_poisson;
  s.materials.silica_strength = bond_strength;
  s.materials.silica_density = density;
  s.materials.titania_youngs_modulus = titania_youngs_modulus;
  s.materials.titania_poisson_ratio = titania_poisson;
  s.materials.titania_strength = titania_strength;
  s.materials.damping = damping;
  s.strain_rate = strain_rate;
  s.quasi_static = quasi_static;
  s.options.max_strain = max_strain;
  s.options.stop_drop = stop_drop;
  s.options.sides = sides;
  s.options.substrate_layers = substrate_layers;
  s.options.time_step = time_step;
  s.options.samples = samples;
  s.options.threads = threads;
  s.snapshot_strains = std::move(snapshot_strains);
  s.finish(model);
  return s;
}

}  // namespace

void bind_uniaxial_compression(py::module_& m) {
  using mechanics::UniaxialCompressionResult;
  py::class_<UniaxialCompressionResult>(m, "UniaxialCompressionResult", "Result of packlab.compress (SI units).")
      .def_readonly("youngs_modulus", &UniaxialCompressionResult::youngs_modulus, "Young's modulus (max-tangent fit) [Pa]")
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
      .def_readonly("stop_reason", &UniaxialCompressionResult::stop_reason)
      .def_readonly("model", &UniaxialCompressionResult::model, "The model after the test (bond states)")
      .def_readonly("seconds", &UniaxialCompressionResult::seconds)
      .def_property_readonly(
          "fit_window", [](const UniaxialCompressionResult& r) { return std::make_pair(r.modulus.strain_begin, r.modulus.strain_end); },
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
            return d;
          },
          "Bond failures: bond index into model.bonds, time [s], position (midpoint) [m]")
      .def_property_readonly(
          "snapshots",
          [](const UniaxialCompressionResult& r) {
            py::list out;
            for (const auto& s : r.snapshots) {
              py::dict d;
              d["strain"] = s.strain;
              d["stress"] = s.stress;
              d["bond_strain"] = to_numpy(std::vector<double>(s.bond_strain));
              std::vector<double> flat;
              for (const auto& a : s.particle_stress) flat.insert(flat.end(), a.begin(), a.end());
              py::array stress = to_numpy(std::move(flat));
              d["particle_stress"] = stress.attr("reshape")(py::make_tuple(static_cast<py::ssize_t>(s.particle_stress.size()), 3, 3));
              py::list types;
              for (const auto& t : analyze::stress_by_type(r.model, s.particle_stress))
                types.append(py::dict(py::arg("type") = t.type, py::arg("particles") = t.particles,
                                      py::arg("mean") = t.mean, py::arg("sd") = t.sd));
              d["stress_by_type"] = types;
              out.append(d);
            }
            return out;
          },
          "Snapshots at snapshot_strains: strain, stress, bond_strain, particle_stress (N x 3 x 3), stress_by_type")
      .def("__repr__", [](const UniaxialCompressionResult& r) {
        return fmt::format("<UniaxialCompressionResult: E = {:.4g} Pa, strength = {:.4g} Pa, {} broken bonds>", r.youngs_modulus,
                           r.strength, r.broken_bonds);
      });

  m.def(
      "compress",
      [](const Packing& model, double bond_youngs_modulus, double bond_poisson, double bond_strength, double density,
         double titania_youngs_modulus, double titania_poisson, double titania_strength, double strain_rate,
         double quasi_static, double max_strain, double stop_drop, const std::string& sides, double substrate_layers,
         double damping, double time_step, long samples, std::vector<double> snapshot_strains, int threads,
         py::object progress, double progress_interval) {
        mechanics::UniaxialCompressionSetup s =
            make_setup(model, bond_youngs_modulus, bond_poisson, bond_strength, density, titania_youngs_modulus,
                       titania_poisson, titania_strength, strain_rate, quasi_static, max_strain, stop_drop, sides,
                       substrate_layers, damping, time_step, samples, std::move(snapshot_strains), threads);
        ProgressCallback callback(progress, progress_interval);
        if (!progress.is_none())
          s.options.on_point = [&](const mechanics::UniaxialCompressionPoint& p) { callback.tick(false, p.strain, p.stress); };
        py::gil_scoped_release nogil;
        return mechanics::run_uniaxial_compression(model, s.options);
      },
      py::arg("model"), py::kw_only(), py::arg("bond_youngs_modulus") = 6.53e9, py::arg("bond_poisson") = 0.17,
      py::arg("bond_strength") = 94.3e6, py::arg("density") = 1297.0, py::arg("titania_youngs_modulus") = 17.89e9,
      py::arg("titania_poisson") = 0.28, py::arg("titania_strength") = 834e6, py::arg("strain_rate") = 0.0,
      py::arg("quasi_static") = 1e-4, py::arg("max_strain") = 0.05, py::arg("stop_drop") = 0.6,
      py::arg("sides") = "periodic", py::arg("substrate_layers") = 2.0, py::arg("damping") = 0.7,
      py::arg("time_step") = 0.0, py::arg("samples") = 400, py::arg("snapshot_strains") = std::vector<double>{},
      py::arg("threads") = 1, py::arg("progress") = py::none(), py::arg("progress_interval") = 0.5, R"doc(
`packlab test compress` from Python: uniaxial compression of a bonded model (bonds in
model.bonds, e.g. from packlab.add_bonds or a .vtu of `packlab bond` / `packlab build opal`) by
a plate moving down at strain_rate [1/s] (0 = automatic: quasi_static strain per elastic-wave
transit). Silica = bond material 0 (and particle types structural/substrate), titania = bond
material 1 (coating particles). Returns a UniaxialCompressionResult (youngs_modulus, strength [Pa],
curve, snapshots, breaks, model). The GIL is released while it runs; progress(strain, stress)
is called at most every progress_interval seconds.
)doc");

  m.def(
      "calibrate_compress",
      [](const Packing& model, double target_youngs_modulus, double target_strength, bool bulk_factor,
         double tolerance, int max_iterations, double relative_step, bool full_jacobian, double bond_youngs_modulus,
         double bond_poisson, double bond_strength, double density, double titania_youngs_modulus,
         double titania_poisson, double titania_strength, double strain_rate, double quasi_static, double max_strain,
         double stop_drop, const std::string& sides, double substrate_layers, double damping, double time_step,
         long samples, int threads, py::object progress) {
        mechanics::UniaxialCompressionSetup s =
            make_setup(model, bond_youngs_modulus, bond_poisson, bond_strength, density, titania_youngs_modulus,
                       titania_poisson, titania_strength, strain_rate, quasi_static, max_strain, stop_drop, sides,
                       substrate_layers, damping, time_step, samples, {}, threads);
        py::dict d;
        if (bulk_factor) {
          mechanics::BulkFactorResult b;
          {
            py::gil_scoped_release nogil;
            b = mechanics::compression_bulk_factor(model, s);
          }
          d["mode"] = "bulk_factor";
          d["bond_youngs_modulus"] = s.materials.silica_youngs_modulus;
          d["bond_strength"] = s.materials.silica_strength;
          d["bulk_factor"] = b.bulk_factor;
          d["strength_ratio"] = b.strength_ratio;
          d["strength_factor"] = b.strength_factor;
          d["youngs_modulus"] = b.run.youngs_modulus;
          d["strength"] = b.run.strength;
          d["final"] = py::cast(std::move(b.run));
          return d;
        }
        mechanics::CalibrationOptions o;
        o.tolerance = tolerance;
        o.max_iterations = max_iterations;
        o.relative_step = relative_step;
        o.diagonal = !full_jacobian;
        auto on_run = [&](int run, const std::vector<double>& p, const mechanics::UniaxialCompressionResult& r) {
          if (progress.is_none()) return;
          py::gil_scoped_acquire gil;
          progress(run, p[0], p[1], r.youngs_modulus, r.strength);
        };
        mechanics::CompressionCalibrationResult result;
        {
          py::gil_scoped_release nogil;
          result = mechanics::calibrate_compression(model, s, target_youngs_modulus, target_strength, o, on_run);
        }
        const mechanics::CalibrationResult& c = result.calibration;
        d["mode"] = "calibrate";
        d["converged"] = c.converged;
        d["reason"] = c.reason();
        d["iterations"] = c.iterations;
        d["simulations"] = c.evaluations;
        d["bond_youngs_modulus"] = c.parameters[0];
        d["bond_strength"] = c.parameters[1];
        d["youngs_modulus"] = c.responses[0];
        d["strength"] = c.responses[1];
        d["history"] = columns_dict(mechanics::calibration_history_columns(c));
        d["final"] = result.has_final ? py::cast(std::move(result.final)) : py::object(py::none());
        return d;
      },
      py::arg("model"), py::kw_only(), py::arg("target_youngs_modulus") = 0.0, py::arg("target_strength") = 0.0,
      py::arg("bulk_factor") = false, py::arg("tolerance") = 0.005, py::arg("max_iterations") = 20,
      py::arg("relative_step") = 0.05, py::arg("full_jacobian") = false, py::arg("bond_youngs_modulus") = 6.53e9,
      py::arg("bond_poisson") = 0.17, py::arg("bond_strength") = 94.3e6, py::arg("density") = 1297.0,
      py::arg("titania_youngs_modulus") = 17.89e9, py::arg("titania_poisson") = 0.28,
      py::arg("titania_strength") = 834e6, py::arg("strain_rate") = 0.0, py::arg("quasi_static") = 1e-4,
      py::arg("max_strain") = 0.05, py::arg("stop_drop") = 0.6, py::arg("sides") = "periodic",
      py::arg("substrate_layers") = 2.0, py::arg("damping") = 0.7, py::arg("time_step") = 0.0,
      py::arg("samples") = 400, py::arg("threads") = 1, py::arg("progress") = py::none(), R"doc(
`packlab calibrate compress` from Python (bpm-inverse-opals eq. 18-20). With the targets:
Newton steps on the silica bond Young's modulus E_b and strength sigma_max (= tau_max), starting
from bond_youngs_modulus and bond_strength, with finite-difference derivatives (relative_step),
until the compression test gives target_youngs_modulus and target_strength [Pa] within
tolerance (relative); the paper's diagonal scheme unless full_jacobian. With bulk_factor=True
(a pore-free sample): one test, K_E = E_macro / E_b. The other keywords are those of
packlab.compress (the automatic strain rate is fixed by the starting E_b, as on the command line).
Returns a dict: mode, bond_youngs_modulus, bond_strength, youngs_modulus, strength, final
(the UniaxialCompressionResult of the result's parameters); calibration: converged, reason, iterations,
simulations, history {bond_youngs_modulus, bond_strength, youngs_modulus, strength,
finite_difference, evaluation} (every simulation in order); bulk factor: bulk_factor, strength_ratio
(E_macro / strength), strength_factor (strength / sigma_max). A calibration that does not
converge returns converged=False. progress(run, E_b, sigma_max, E, strength) is called after
each simulation.
)doc");

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
