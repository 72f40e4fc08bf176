// Generators of issues #3/#4: void expansion method (vem), Lubachevsky-Stillinger (ls),
// shaking (shake) and their combination (scrm), with keywords named like the command-line
// options. Each returns a types.SimpleNamespace with the packing and what the report holds.
#include <fmt/format.h>

#include <sstream>

#include "common.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/ls.hpp"
#include "packlab/generate/scrm.hpp"
#include "packlab/generate/shake.hpp"
#include "packlab/generate/vem.hpp"

namespace packlab::python {

namespace {

py::object namespace_of(py::dict values) { return py::module_::import("types").attr("SimpleNamespace")(**values); }

generate::SizeClasses size_classes(const std::vector<double>& sizes, const std::vector<double>& number_fractions,
                                   const std::vector<double>& volume_fractions) {
  return generate::SizeClasses::from_options(sizes, number_fractions, volume_fractions);
}

py::dict ls_status(const generate::LsStatus& s) {
  py::dict d;
  d["stop"] = generate::ls_stop_name(s.stop);
  d["volume_fraction"] = s.volume_fraction;
  d["reduced_pressure"] = s.reduced_pressure;
  d["blocks"] = s.blocks;
  d["collisions"] = s.collisions;
  d["transfers"] = s.transfers;
  d["stale_events"] = s.stale;
  d["simulated_time"] = s.time;
  d["seconds"] = s.seconds;
  return d;
}

py::dict shake_stats(const generate::ShakeStats& s) {
  py::dict d;
  d["sweeps"] = s.sweeps;
  d["visits"] = s.visits;
  d["trials"] = s.trials;
  d["moves"] = s.moves;
  d["mean_step"] = s.mean_step;
  d["seconds"] = s.seconds;
  d["window"] = s.window;
  return d;
}

generate::ShakeParams shake_params(double window, int max_trials, bool adaptive) {
  generate::ShakeParams s;
  s.window = window;
  s.max_trials = max_trials;
  s.adaptive = adaptive;
  s.validate();
  return s;
}

const char* ls_doc = R"doc(
phi: target volume fraction (0 = grow until jammed); particles; sizes: relative diameters of
the size classes (e.g. [1, 0.313]); number_fractions or volume_fractions (one of them,
normalized; empty = equal numbers); radius: radius of the largest class at the target [m];
growth_rate: G = ds/dt; max_pressure: jamming criterion (reduced pressure PV/NkT);
events_per_block; seed. progress(block, volume_fraction, reduced_pressure) is called (GIL
held, at most every progress_interval s) after LS blocks.
)doc";

}  // namespace

void bind_generate_later(py::module_& m) {
  // --- vem (issue 3) ---
  m.def(
      "generate_vem",
      [](long structural, long voids, double phi_s, double radius, std::uint64_t seed, int threads, double max_q,
         int blowup_steps, double void_radius_ratio, double contact_eps, double relax_tolerance, long relax_max_steps,
         double void_mass_scaling, double stop_strain_energy, const std::string& time_step_rule,
         double time_step_safety, double skin,
         std::optional<dem::Material> structural_material, std::optional<dem::Material> void_material,
         py::object progress, double progress_interval) {
        generate::VemParams p;
        p.structural = structural;
        p.voids = voids;
        p.phi_s = phi_s;
        p.radius = radius;
        p.seed = seed;
        p.threads = threads;
        p.max_q = max_q;
        p.blowup_steps = blowup_steps;
        p.void_radius_ratio = void_radius_ratio;
        p.contact_eps = contact_eps;
        p.relax_tolerance = relax_tolerance;
        p.relax_max_steps = relax_max_steps;
        p.void_mass_scaling = void_mass_scaling;
        p.stop_strain_energy = stop_strain_energy;
        p.time_step_rule = time_step_rule;
        p.time_step_safety = time_step_safety;
        p.skin = skin;
        if (structural_material) p.structural_material = *structural_material;
        if (void_material) p.void_material = *void_material;
        p.validate();
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
      py::kw_only(), py::arg("structural") = 8000, py::arg("voids") = 2000, py::arg("phi_s") = 0.4,
      py::arg("radius") = 2.5e-7, py::arg("seed") = 1, py::arg("threads") = 0, py::arg("max_q") = 3.0,
      py::arg("blowup_steps") = 10, py::arg("void_radius_ratio") = 0.005, py::arg("contact_eps") = 0.01,
      py::arg("relax_tolerance") = 1e-2, py::arg("relax_max_steps") = 20000, py::arg("void_mass_scaling") = 1.0,
      py::arg("stop_strain_energy") = 1e-3, py::arg("time_step_rule") = "stiffness_sum",
      py::arg("time_step_safety") = 0.8, py::arg("skin") = 0.2,
      py::arg("structural_material") = py::none(), py::arg("void_material") = py::none(),
      py::arg("progress") = py::none(), py::arg("progress_interval") = 0.5, R"doc(
`packlab generate vem`: the void expansion method (docs/vem.md). Keywords as the config keys:
structural N_S, voids N_V, phi_s, radius r_S [m], seed, threads, max_q, blowup_steps m,
void_radius_ratio r_V0/r_S, contact_eps, relax_tolerance, relax_max_steps, void_mass_scaling,
stop_strain_energy, time_step_rule ("stiffness_sum" or "contacts"), time_step_safety, skin;
structural_material / void_material: Material
(default Table 1: k_n 1e3 / 1e2 N/m, k_s 1e-2 N/m, density 3690 / 369 kg/m^3, damping 0.7).
progress(cycle, q, cn) (q = cn = -1 between rows). Returns a namespace: packing (structural
particles, voids removed), curve (dict of arrays: the columns of cn_curve.csv), stop, steps,
seconds, number_ratio. find_inflection(curve["q"], curve["cn"]) gives the inflection point.
)doc");

  // --- ls (issue 4) ---
  m.def(
      "generate_ls",
      [](double phi, long particles, std::vector<double> sizes, std::vector<double> number_fractions,
         std::vector<double> volume_fractions, double radius, double growth_rate, double max_pressure,
         double events_per_block, std::uint64_t seed, py::object progress, double progress_interval) {
        const generate::SizeClasses classes = size_classes(sizes, number_fractions, volume_fractions);
        generate::LsParams p;
        p.growth_rate = growth_rate;
        p.max_reduced_pressure = max_pressure;
        p.events_per_block = events_per_block;
        p.target_volume_fraction = phi;
        p.validate();
        ProgressCallback callback(progress, progress_interval);
        std::vector<double> log_phi, log_pressure, log_time;
        std::vector<long> log_block;
        Packing packing;
        generate::LsStatus status;
        {
          py::gil_scoped_release nogil;
          Random rng(seed);
          const generate::LsStart start = generate::make_ls_start(particles, classes, radius, phi > 0 ? phi : 0.64, rng);
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
      py::kw_only(), py::arg("phi") = 0.0, py::arg("particles") = 2000, py::arg("sizes") = std::vector<double>{1.0},
      py::arg("number_fractions") = std::vector<double>{}, py::arg("volume_fractions") = std::vector<double>{},
      py::arg("radius") = 0.5, py::arg("growth_rate") = 0.01, py::arg("max_pressure") = 1e12,
      py::arg("events_per_block") = 20.0, py::arg("seed") = 1, py::arg("progress") = py::none(),
      py::arg("progress_interval") = 0.5,
      (std::string("`packlab generate ls`: Lubachevsky-Stillinger growth of hard spheres from random points.\n") +
       ls_doc +
       "Returns a namespace: packing, stop, volume_fraction, reduced_pressure, blocks, collisions, transfers, "
       "simulated_time, seconds, log (dict of arrays per block).")
          .c_str());

  // --- shake (issue 4) ---
  m.def(
      "shake",
      [](const Packing& packing, long sweeps, double window, int max_trials, bool adaptive, std::uint64_t seed,
         py::object progress, double progress_interval) {
        const generate::ShakeParams sp = shake_params(window, max_trials, adaptive);
        require(sweeps >= 0, "sweeps", static_cast<double>(sweeps), ">= 0");
        ProgressCallback callback(progress, progress_interval);
        Packing out = packing;
        generate::ShakeStats stats;
        {
          py::gil_scoped_release nogil;
          Random rng(seed);
          generate::Shaker shaker(out, sp);
          shaker.sweeps(sweeps, rng, [&](const generate::ShakeStats& s) {
            const long done = s.sweeps;
            callback.tick(false, done, sweeps);
          });
          stats = shaker.stats();
        }
        py::dict values = shake_stats(stats);
        values["packing"] = std::move(out);
        return namespace_of(values);
      },
      py::arg("packing"), py::kw_only(), py::arg("sweeps") = 100, py::arg("window") = 0.02, py::arg("max_trials") = 150,
      py::arg("adaptive") = false, py::arg("seed") = 1, py::arg("progress") = py::none(),
      py::arg("progress_interval") = 0.5, R"doc(
`packlab shake`: Monte-Carlo shaking of a packing without overlaps (a copy; the input is
unchanged). sweeps: global shakes M; window: shake window R_sh in particle radii; max_trials:
trials per visit N_sh; adaptive: adapt the window; seed. progress(done, total) after sweeps.
Returns a namespace: packing, sweeps, visits, trials, moves, mean_step, seconds, window.
)doc");

  // --- scrm (issue 4) ---
  m.def(
      "generate_scrm",
      [](double phi, long particles, std::vector<double> sizes, std::vector<double> number_fractions,
         std::vector<double> volume_fractions, double radius, double growth_rate, double max_pressure,
         double events_per_block, double window, int max_trials, bool adaptive, long blocks_per_cycle,
         long shakes_per_cycle, long final_shakes, std::uint64_t seed, py::object progress,
         double progress_interval) {
        const generate::SizeClasses classes = size_classes(sizes, number_fractions, volume_fractions);
        generate::ScrmParams sp;
        sp.ls.growth_rate = growth_rate;
        sp.ls.max_reduced_pressure = max_pressure;
        sp.ls.events_per_block = events_per_block;
        sp.ls.target_volume_fraction = phi;
        sp.shake = shake_params(window, max_trials, adaptive);
        sp.blocks_per_cycle = blocks_per_cycle;
        sp.shakes_per_cycle = shakes_per_cycle;
        sp.final_shakes = final_shakes;
        sp.validate();
        ProgressCallback callback(progress, progress_interval);
        generate::ScrmResult r;
        {
          py::gil_scoped_release nogil;
          Random rng(seed);
          const generate::LsStart start = generate::make_ls_start(particles, classes, radius, phi, rng);
          generate::LsSimulation sim(start.box, start.points, start.unit_radius, sp.ls, rng);
          r = run_scrm(sim, sp, rng, [&](const generate::LsStatus& ls, const generate::ShakeStats&) {
            const double volume_fraction = ls.volume_fraction;
            callback.tick(false, volume_fraction, phi);
          });
        }
        py::dict values;
        values["packing"] = std::move(r.packing);
        values["ls"] = ls_status(r.ls);
        values["shake"] = shake_stats(r.shake);
        values["cycles"] = r.cycles;
        return namespace_of(values);
      },
      py::kw_only(), py::arg("phi"), py::arg("particles") = 2000, py::arg("sizes") = std::vector<double>{1.0},
      py::arg("number_fractions") = std::vector<double>{}, py::arg("volume_fractions") = std::vector<double>{},
      py::arg("radius") = 0.5, py::arg("growth_rate") = 0.01, py::arg("max_pressure") = 1e12,
      py::arg("events_per_block") = 20.0, py::arg("window") = 0.02, py::arg("max_trials") = 150,
      py::arg("adaptive") = false, py::arg("blocks_per_cycle") = 5, py::arg("shakes_per_cycle") = 1,
      py::arg("final_shakes") = 10, py::arg("seed") = 1, py::arg("progress") = py::none(),
      py::arg("progress_interval") = 0.5,
      (std::string("`packlab generate scrm`: LS growth alternated with shaking, to the volume fraction phi.\n") +
       ls_doc +
       "window, max_trials, adaptive: as shake(); blocks_per_cycle: LS blocks between shakes; shakes_per_cycle; "
       "final_shakes: global shakes at the target. progress(volume_fraction, phi). Returns a namespace: packing, "
       "ls (dict), shake (dict), cycles.")
          .c_str());
}

}  // namespace packlab::python
