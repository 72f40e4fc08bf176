// packlab.Material, BondMaterial, Diagnostics, Engine, relax: the DEM engine with keyword
// arguments named like the options of `packlab relax`. Long runs release the GIL; the
// optional progress callback is called (throttled) with the GIL held.
#include <fmt/format.h>

#include <deque>
#include <sstream>

#include "common.hpp"
#include "packlab/core/error.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/dem/relax.hpp"
#include "packlab/io/options.hpp"

namespace packlab::python {

namespace {

using dem::Diagnostics;
using dem::Engine;
using dem::EngineConfig;
using dem::Material;

// Diagnostics of a run as a dict of arrays: the columns of `packlab relax --log`.
py::dict history_columns(const std::vector<Diagnostics>& history) {
  std::vector<long> step;
  std::vector<double> time, kinetic, strain, ratio, cn, overlap;
  std::vector<long> contacts, intact, broken;
  for (const auto& d : history) {
    step.push_back(d.step);
    time.push_back(d.time);
    kinetic.push_back(d.kinetic_energy);
    strain.push_back(d.strain_energy);
    ratio.push_back(d.unbalanced_force_ratio);
    cn.push_back(d.mean_coordination);
    contacts.push_back(static_cast<long>(d.contacts));
    overlap.push_back(d.max_overlap_ratio);
    intact.push_back(static_cast<long>(d.intact_bonds));
    broken.push_back(static_cast<long>(d.broken_bonds));
  }
  py::dict out;
  out["step"] = to_numpy(std::move(step));
  out["time"] = to_numpy(std::move(time));
  out["kinetic_energy"] = to_numpy(std::move(kinetic));
  out["strain_energy"] = to_numpy(std::move(strain));
  out["unbalanced_force_ratio"] = to_numpy(std::move(ratio));
  out["mean_coordination"] = to_numpy(std::move(cn));
  out["contacts"] = to_numpy(std::move(contacts));
  out["max_overlap_ratio"] = to_numpy(std::move(overlap));
  out["intact_bonds"] = to_numpy(std::move(intact));
  out["broken_bonds"] = to_numpy(std::move(broken));
  return out;
}

struct RelaxOutcome {
  Packing packing;
  long steps = 0;
  bool converged = false;
  std::string reason;
  double time_step = 0.0;
  Diagnostics last;
  std::vector<Diagnostics> history;
};

// Runs dem::relax with the GIL released; progress(step, total_steps, diagnostics).
dem::RelaxResult relax_engine(Engine& engine, long steps, double tolerance, long check_interval,
                              const py::object& progress, double progress_interval) {
  ProgressCallback callback(progress, progress_interval);
  dem::RelaxOptions ro;
  ro.max_steps = steps;
  ro.tolerance = tolerance;
  ro.check_interval = check_interval;
  ro.on_check = [&](const Diagnostics& d) { callback.tick(false, d.step, steps, d); };
  dem::RelaxResult result;
  {
    py::gil_scoped_release nogil;
    result = dem::relax(engine, ro);
  }
  if (!progress.is_none()) progress(result.last.step, steps, result.last);
  return result;
}

// The bonds of an engine: `bond_law` must be the contact bond (BondMaterial parameters).
void set_bond_materials(EngineConfig& c, const std::string& bond_law,
                        const std::optional<std::vector<dem::ContactBond::Params>>& bond_materials) {
  if (bond_law != dem::ContactBond::name)
    packlab::fail_input(
        fmt::format("bond_law = {}: Engine takes '{}' bonds (BondMaterial)", bond_law, dem::ContactBond::name));
  if (bond_materials) c.bond_materials = *bond_materials;
}

// The keywords of Material(...): every property of dem::material_parameters().
io::ConfigSchema material_keywords(Material& t) {
  io::ConfigSchema schema("Material", "", "Material");
  schema.parameters("", t, dem::material_parameters());
  return schema;
}

}  // namespace

void bind_dem(py::module_& m) {
  Material material_defaults;
  static const std::string material_doc =
      "Material(**keywords): the properties of one particle type that the contact laws read (see Engine). " +
      keywords_doc(material_keywords(material_defaults));
  py::class_<Material> material(m, "Material", material_doc.c_str());
  material.def(py::init([](const py::kwargs& kwargs) {
    Material t;
    apply_keywords(material_keywords(t), kwargs, "Material");
    return t;
  }));
  static std::deque<std::string> property_docs;  // pybind11 keeps the pointers
  for (const Parameter<Material>& p : dem::material_parameters()) {
    property_docs.push_back(std::string(p.doc) + (p.unit.empty() ? "" : " [" + std::string(p.unit) + "]"));
    property_docs.push_back(std::string(p.name));
    material.def_property(
        property_docs.back().c_str(), [p](const Material& t) { return p.get(t); },
        [p](Material& t, double v) { p.set(t, v); }, property_docs[property_docs.size() - 2].c_str());
  }
  material.def("__repr__", [](const Material& t) {
    return fmt::format(
        "Material(normal_stiffness={:g}, shear_stiffness={:g}, friction={:g}, density={:g}, "
        "damping={:g})",
        t.normal_stiffness, t.shear_stiffness, t.friction, t.density, t.damping);
  });

  using BondParams = dem::ContactBond::Params;
  py::class_<BondParams>(m, "BondMaterial",
                         "Parameters of the PFC contact bond: normal_stiffness, shear_stiffness [N/m], "
                         "normal_strength (tension), shear_strength [N].")
      .def(py::init([](double kn, double ks, double fn, double fs) {
             return BondParams{kn, ks, fn, fs};
           }),
           py::kw_only(), py::arg("normal_stiffness"), py::arg("shear_stiffness"), py::arg("normal_strength"),
           py::arg("shear_strength"))
      .def_readwrite("normal_stiffness", &BondParams::normal_stiffness, "k_n [N/m]")
      .def_readwrite("shear_stiffness", &BondParams::shear_stiffness, "k_s [N/m]")
      .def_readwrite("normal_strength", &BondParams::normal_strength, "F_nB [N]")
      .def_readwrite("shear_strength", &BondParams::shear_strength, "F_sB [N]");

  py::class_<Diagnostics>(m, "Diagnostics", "The engine's diagnostics at one step (SI units).")
      .def_readonly("step", &Diagnostics::step)
      .def_readonly("time", &Diagnostics::time, "[s]")
      .def_readonly("kinetic_energy", &Diagnostics::kinetic_energy, "translational + rotational [J]")
      .def_readonly("strain_energy", &Diagnostics::strain_energy, "elastic energy in contacts [J]")
      .def_readonly("unbalanced_force_ratio", &Diagnostics::unbalanced_force_ratio,
                    "mean |F_i| over free particles / mean contact force")
      .def_readonly("mean_coordination", &Diagnostics::mean_coordination, "2 contacts / particles")
      .def_readonly("contacts", &Diagnostics::contacts, "touching pairs")
      .def_readonly("max_overlap_ratio", &Diagnostics::max_overlap_ratio, "max overlap / (r_i + r_j)")
      .def_readonly("intact_bonds", &Diagnostics::intact_bonds)
      .def_readonly("broken_bonds", &Diagnostics::broken_bonds)
      .def("__repr__", [](const Diagnostics& d) {
        return fmt::format("<Diagnostics step {}: unbalanced {:.3g}, CN {:.3f}, kinetic {:.3g} J, strain {:.3g} J>",
                           d.step, d.unbalanced_force_ratio, d.mean_coordination, d.kinetic_energy, d.strain_energy);
      });

  m.def("contact_law_names", &dem::contact_law_names, "Names of the registered contact laws.");

  io::EngineSettings engine_defaults;
  static const std::string engine_doc = R"doc(
The DEM engine: soft spheres, leap-frog integration, Verlet neighbour list, contact laws,
local damping, bonds, walls. Engine(packing, **keywords) copies the packing; `packing()`
returns its current state. The material keywords apply to every particle type; `materials`
(one Material per type) replaces them. bond_law: "contact"; bond_materials: list of
BondMaterial (one per bond material), required when the packing has intact bonds.
)doc" + keywords_doc(io::engine_options(engine_defaults));
  py::class_<Engine>(m, "Engine", engine_doc.c_str())
      .def(py::init([](const Packing& packing, std::optional<std::vector<Material>> materials,
                       const std::string& bond_law, std::optional<std::vector<dem::ContactBond::Params>> bond_materials,
                       const py::kwargs& kwargs) {
             io::EngineSettings settings;
             apply_keywords(io::engine_options(settings), kwargs, "Engine");
             EngineConfig c = settings.config();
             if (materials) c.types = *materials;
             set_bond_materials(c, bond_law, bond_materials);
             py::gil_scoped_release nogil;
             return std::make_unique<Engine>(packing, c);
           }),
           py::arg("packing"), py::kw_only(), py::arg("materials") = py::none(),
           py::arg("bond_law") = std::string(dem::ContactBond::name), py::arg("bond_materials") = py::none())
      .def("run", &Engine::run, py::arg("steps"), py::call_guard<py::gil_scoped_release>(),
           "Advances `steps` steps (GIL released).")
      .def("step", &Engine::step_measured, py::call_guard<py::gil_scoped_release>(),
           "Advances one step; returns the Diagnostics of the state at its start.")
      .def(
          "relax",
          [](Engine& e, long steps, double tolerance, long check_interval, py::object progress,
             double progress_interval) {
            const dem::RelaxResult r = relax_engine(e, steps, tolerance, check_interval, progress, progress_interval);
            py::dict out;
            out["steps"] = r.steps;
            out["converged"] = r.stop == dem::RelaxStop::converged;
            out["reason"] = r.reason();
            out["last"] = r.last;
            out["history"] = history_columns(r.history);
            return out;
          },
          py::kw_only(), py::arg("steps") = 100000, py::arg("tolerance") = 1e-3, py::arg("check_interval") = 100,
          py::arg("progress") = py::none(), py::arg("progress_interval") = 0.5,
          "Runs until the unbalanced force ratio < tolerance or `steps` steps; returns a dict "
          "(steps, converged, reason, last, history). See packlab.relax for progress.")
      .def_property("time_step", &Engine::time_step, &Engine::set_time_step, "Current time step [s].")
      .def("critical_time_step", &Engine::critical_time_step,
           "safety * min over particles of sqrt(m_i / k_i) for the current particles [s].")
      .def_property_readonly("step_count", &Engine::step_count)
      .def_property_readonly("time", &Engine::time, "[s]")
      .def_property_readonly("threads", &Engine::threads, "The thread count as configured (0 resolved).")
      .def_property_readonly("active_threads", &Engine::active_threads,
                             "The thread count of the next step: 1 or `threads` (adapt_threads: an adapting engine "
                             "starts at one and goes up while probes find more threads faster).")
      .def_property_readonly("intact_bonds", &Engine::intact_bonds)
      .def("__len__", &Engine::particle_count)
      .def("packing", &Engine::packing,
           "The packing (original particle order) with current positions and velocities (a copy).")
      .def("set_radius_of_type", &Engine::set_radius_of_type, py::arg("type"), py::arg("radius"),
           "Sets the radius [m] of every particle of `type` (mass follows at constant density).")
      .def(
          "set_radii", [](Engine& e, py::object r) { e.set_radii(from_numpy<double>(r, "radii")); }, py::arg("radii"),
          "Sets every radius [m] (packing order).")
      .def(
          "contact_forces",
          [](const Engine& e) {
            dem::ContactForces f = e.contact_forces();
            py::dict out;
            out["i"] = to_numpy(std::move(f.i));
            out["j"] = to_numpy(std::move(f.j));
            out["kind"] = to_numpy(std::move(f.kind));
            out["branch"] = to_numpy(std::move(f.branch));
            out["force"] = to_numpy(std::move(f.force));
            return out;
          },
          R"doc(Every force between bodies now, as a dict of arrays: i, j (packing order; j = -1 - wall for
wall contacts), kind (0 contact, 1 bond, 2 wall), branch (M x 3, centre i to centre j [m]),
force (M x 3, force on j [N]).)doc")
      .def(
          "particle_stress",
          [](const Engine& e) {
            const auto s = dem::particle_stress(e.contact_forces(), e.packing());
            py::array_t<double> out({static_cast<py::ssize_t>(s.size()), py::ssize_t{3}, py::ssize_t{3}});
            auto w = out.mutable_unchecked<3>();
            for (std::size_t k = 0; k < s.size(); ++k)
              for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                  w(static_cast<py::ssize_t>(k), a, b) = s[k][static_cast<std::size_t>(3 * a + b)];
            return out;
          },
          "Per-particle Cauchy stress sigma_ab = 1/(2 V_p) sum l_a F_b, N x 3 x 3, tension positive [Pa].")
      .def(
          "add_wall",
          [](Engine& e, std::array<double, 3> point, std::array<double, 3> normal, std::array<double, 3> velocity) {
            dem::Wall w;
            w.point = to_vec3(point);
            w.normal = to_vec3(normal);
            w.velocity = to_vec3(velocity);
            return e.add_wall(w);
          },
          py::arg("point"), py::arg("normal") = std::array<double, 3>{0, 0, 1},
          py::arg("velocity") = std::array<double, 3>{0, 0, 0},
          "Adds a plane wall (point [m], unit normal into the particles' side, velocity [m/s]); returns its index.")
      .def(
          "set_wall_velocity",
          [](Engine& e, std::size_t k, std::array<double, 3> v) { e.wall(k).velocity = to_vec3(v); }, py::arg("wall"),
          py::arg("velocity"), "Sets the velocity [m/s] of wall `wall`.")
      .def(
          "wall_position",
          [](const Engine& e, std::size_t k) {
            return py::make_tuple(e.wall(k).point.x, e.wall(k).point.y, e.wall(k).point.z);
          },
          py::arg("wall"), "A point on the wall now [m].")
      .def(
          "wall_force",
          [](const Engine& e, std::size_t k) {
            const Vec3& f = e.wall_force(k);
            return py::make_tuple(f.x, f.y, f.z);
          },
          py::arg("wall"), "Force the particles exerted on wall `wall` during the last step [N].")
      .def_property_readonly("wall_count", &Engine::wall_count)
      .def(
          "save_state",
          [](const Engine& e) {
            std::ostringstream out(std::ios::binary);
            e.save_state(out);
            return py::bytes(out.str());
          },
          "The whole dynamic state as bytes (an engine built from the same packing and keywords continues "
          "exactly after load_state).")
      .def(
          "load_state",
          [](Engine& e, const py::bytes& state) {
            std::istringstream in(std::string(state), std::ios::binary);
            e.load_state(in);
          },
          py::arg("state"));

  py::class_<RelaxOutcome>(m, "RelaxResult", "Result of packlab.relax.")
      .def_readonly("packing", &RelaxOutcome::packing, "The relaxed packing.")
      .def_readonly("steps", &RelaxOutcome::steps, "Steps run.")
      .def_readonly("converged", &RelaxOutcome::converged, "True if the tolerance was met (else: step limit).")
      .def_readonly("reason", &RelaxOutcome::reason, "The line `packlab relax` prints.")
      .def_readonly("time_step", &RelaxOutcome::time_step, "[s]")
      .def_readonly("last", &RelaxOutcome::last, "Diagnostics at the last check.")
      .def_property_readonly(
          "history", [](const RelaxOutcome& r) { return history_columns(r.history); },
          "Diagnostics of every check as a dict of arrays (the columns of `packlab relax --log`).")
      .def("__repr__", [](const RelaxOutcome& r) { return fmt::format("<RelaxResult: {}>", r.reason); });

  io::RelaxRun relax_defaults;
  static const std::string relax_doc = R"doc(
`packlab relax` from Python: relaxes a copy of the packing with the contact law and local
damping until the mean unbalanced force ratio falls below `tolerance` (0 = run exactly `steps`
steps) or `steps` steps ran; returns a RelaxResult (packing, steps, converged, reason,
time_step, last, history). `materials` (one Material per particle type) replaces the material
keywords. The GIL is released while it runs; progress(step, total_steps, diagnostics) is called
with the GIL held at most every progress_interval seconds and once at the end; an exception in
it (or Ctrl-C) stops the run.
)doc" + keywords_doc(io::relax_options(relax_defaults));
  m.def(
      "relax",
      [](const Packing& packing, std::optional<std::vector<Material>> materials, py::object progress,
         double progress_interval, const py::kwargs& kwargs) {
        io::RelaxRun run;
        apply_keywords(io::relax_options(run), kwargs, "relax");
        EngineConfig c = run.config();
        if (materials) c.types = *materials;
        const long steps = run.relax.max_steps;
        const double tolerance = run.relax.tolerance;
        const long check_interval = run.relax.check_interval;
        std::unique_ptr<Engine> engine;
        {
          py::gil_scoped_release nogil;
          engine = std::make_unique<Engine>(packing, c);
        }
        const dem::RelaxResult r = relax_engine(*engine, steps, tolerance, check_interval, progress, progress_interval);
        RelaxOutcome out;
        out.packing = engine->packing();
        out.steps = r.steps;
        out.converged = r.stop == dem::RelaxStop::converged;
        out.reason = r.reason();
        out.time_step = engine->time_step();
        out.last = r.last;
        out.history = r.history;
        return out;
      },
      py::arg("packing"), py::kw_only(), py::arg("materials") = py::none(), py::arg("progress") = py::none(),
      py::arg("progress_interval") = 0.5, relax_doc.c_str());
}

}  // namespace packlab::python
