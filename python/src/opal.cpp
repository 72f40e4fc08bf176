// Issue #7 (structure side): the force-biased algorithm (packlab.generate_fba) and the
// inverse-opal builder (packlab.build_opal), keywords named like the command-line options.
// Each returns a types.SimpleNamespace with the packing / model and what the report holds.
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "common.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/generate/opal.hpp"

namespace packlab::python {

namespace {

py::object namespace_of(py::dict values) { return py::module_::import("types").attr("SimpleNamespace")(**values); }

}  // namespace

void bind_opal(py::module_& m) {
  m.def(
      "generate_fba",
      [](long particles, std::optional<std::array<double, 3>> box, std::array<double, 3> aspect, double diameter,
         double porosity, std::vector<double> sizes, std::vector<double> number_fractions,
         std::vector<double> volume_fractions, const std::string& periodic, double tolerance, double shrink_rate,
         double step, long max_iterations, std::uint64_t seed, int threads, long history_every, py::object progress,
         double progress_interval) {
        const generate::SizeClasses classes =
            generate::SizeClasses::from_options(sizes, number_fractions, volume_fractions);
        generate::FbaParams p;
        p.target_porosity = porosity;
        p.tolerance = tolerance;
        p.shrink_rate = shrink_rate;
        p.step = step;
        p.max_iterations = max_iterations;
        p.threads = threads;
        p.validate();
        require(diameter > 0.0 && std::isfinite(diameter), "diameter", diameter, "> 0 m");
        if ((particles > 0) == box.has_value()) fail_input("particles and box: give exactly one of them");
        Box b;
        b.periodic = generate::periodic_axes_from_name(periodic);
        long n = particles;
        if (box) {
          for (double l : *box) require(l > 0.0, "box", l, "> 0 m");
          b.length = to_vec3(*box);
          n = generate::fba_count_for_volume(b.volume(), porosity, diameter, classes);
        } else {
          require(n >= 2 && n <= 100'000'000, "particles", static_cast<double>(n), "in [2, 1e8]");
          for (double a : aspect) require(a > 0.0, "aspect", a, "> 0");
          const std::vector<double> x = classes.number_fractions();
          const double smax = *std::max_element(classes.sizes.begin(), classes.sizes.end());
          double mean_volume = 0;
          for (std::size_t k = 0; k < x.size(); ++k)
            mean_volume += x[k] * std::numbers::pi / 6.0 * std::pow(classes.sizes[k] / smax * diameter, 3);
          const double s = std::cbrt(static_cast<double>(n) * mean_volume / (1.0 - porosity) /
                                     (aspect[0] * aspect[1] * aspect[2]));
          b.length = {aspect[0] * s, aspect[1] * s, aspect[2] * s};
        }
        ProgressCallback callback(progress, progress_interval);
        generate::FbaResult r;
        {
          py::gil_scoped_release nogil;
          Random rng(seed);
          const std::vector<double> rho = generate::fba_class_radii(n, classes, rng);
          r = generate::fba_pack(b, rho, p, rng, history_every, [&](const generate::FbaStatus& s) {
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
      py::kw_only(), py::arg("particles") = 0, py::arg("box") = py::none(),
      py::arg("aspect") = std::array<double, 3>{1, 1, 1}, py::arg("diameter") = 1.0, py::arg("porosity") = 0.38,
      py::arg("sizes") = std::vector<double>{1.0}, py::arg("number_fractions") = std::vector<double>{},
      py::arg("volume_fractions") = std::vector<double>{}, py::arg("periodic") = "xyz", py::arg("tolerance") = 1e-3,
      py::arg("shrink_rate") = 0.01, py::arg("step") = 1.0, py::arg("max_iterations") = 100000, py::arg("seed") = 1,
      py::arg("threads") = 1, py::arg("history_every") = 10, py::arg("progress") = py::none(),
      py::arg("progress_interval") = 0.5, R"doc(
`packlab generate fba`: force-biased algorithm (docs/opal-build.md). Give particles (the box
follows from diameter, porosity and aspect) or box=(LX, LY, LZ) [m] (the count follows).
diameter: of the largest class [m]; porosity: target 1 - sum V / V_box; sizes /
number_fractions / volume_fractions: size classes; periodic: subset of "xyz" or "none" (walls
on the others); tolerance: accepted max overlap / (r_i + r_j); shrink_rate, step,
max_iterations, seed, threads; history_every: iterations between history rows.
progress(iteration, max_overlap, outer_scale). Returns a namespace: packing, porosity, stop
("target_reached" or "max_iterations"), iterations, max_overlap, verified_max_overlap (an
independent pair search), seconds, history (dict of arrays).
)doc");

  m.def(
      "build_opal",
      [](const Packing& packing, const std::string& pores, double pore_diameter, double pore_ratio,
         const std::string& orientation, double pore_spacing, std::optional<std::array<double, 3>> pore_origin,
         long pore_count, double pore_fraction, py::object pore_centres, py::object pore_radii, double coating,
         double opening_distance_ratio, double substrate_layers, double bond_cutoff, double bond_radius_ratio,
         double silica_density, double titania_density, std::uint64_t seed, int threads) {
        require(packing.size() >= 1, "particles", 0, ">= 1 in the input packing");
        generate::OpalOptions o;
        o.coating_thickness = coating;
        o.opening_distance_ratio = opening_distance_ratio;
        o.substrate_layers = substrate_layers;
        o.bond_cutoff_ratio = bond_cutoff;
        o.bond_radius_ratio = bond_radius_ratio;
        o.silica_density = silica_density;
        o.titania_density = titania_density;
        o.threads = threads;
        double mean_d = 0;
        for (double r : packing.radius) mean_d += 2.0 * r;
        mean_d /= static_cast<double>(packing.size());
        if (pores == "list") {
          if (pore_centres.is_none() || pore_radii.is_none())
            fail_input("pores = list: give pore_centres (N x 3) and pore_radii (N)");
          o.pores.centre = vec3s_from_numpy(pore_centres, "pore_centres");
          o.pores.radius =
              from_numpy<double>(pore_radii, "pore_radii", static_cast<py::ssize_t>(o.pores.centre.size()));
        } else {
          if ((pore_diameter > 0.0) == (pore_ratio > 0.0))
            fail_input("pore_diameter and pore_ratio: give exactly one of them (> 0)");
          const double D = pore_diameter > 0.0 ? pore_diameter : pore_ratio * mean_d;
          if (pores == "fcc") {
            o.fcc.diameter = D;
            o.fcc.orientation = generate::fcc_orientation_from_name(orientation);
            o.fcc.spacing_ratio = pore_spacing;
            if (pore_origin) {
              o.fcc.auto_origin = false;
              o.fcc.origin = to_vec3(*pore_origin);
            }
          } else if (pores == "random") {
            if ((pore_count > 0) == (pore_fraction > 0.0))
              fail_input("pore_count and pore_fraction: give exactly one of them with pores = random");
            const Box region = generate::random_pore_region(packing, substrate_layers);
            generate::RandomPores rp;
            rp.diameter = D;
            if (pore_fraction > 0.0) {
              require(pore_fraction < 0.6, "pore_fraction", pore_fraction, "in (0, 0.6)");
              rp.count = std::max(
                  1L, std::lround(pore_fraction * region.volume() / (std::numbers::pi / 6.0 * D * D * D)));
            } else {
              rp.count = pore_count;
            }
            Random rng(seed);
            py::gil_scoped_release nogil;
            o.pores = generate::random_pores(region, rp, rng);
          } else {
            fail_input("pores = " + pores + ": must be one of fcc, random, list");
          }
        }
        generate::OpalSummary s;
        Packing model;
        generate::PoreSet set;
        {
          py::gil_scoped_release nogil;
          model = generate::build_opal(packing, o, &s);
          set = generate::opal_pores(packing, o);
        }
        py::dict values;
        values["packing"] = std::move(model);
        values["pore_centres"] = py::array_t<double>(
            {static_cast<py::ssize_t>(set.size()), py::ssize_t{3}},
            reinterpret_cast<const double*>(set.centre.data()));
        values["pore_radii"] = to_numpy(std::move(set.radius));
        values["input_particles"] = s.input_particles;
        values["particles"] = s.particles;
        values["silica_particles"] = s.structural;
        values["titania_particles"] = s.coating;
        values["substrate_particles"] = s.substrate;
        values["removed_particles"] = s.removed;
        values["coating_dropped_at_openings"] = s.coating_openings;
        values["pores"] = s.pores;
        values["bonds"] = s.bonds;
        values["bonds_by_material"] = s.bonds_by_material;
        values["periodic_bonds"] = s.periodic_bonds;
        values["mean_coordination"] = s.mean_coordination;
        values["porosity"] = s.porosity;
        values["particle_porosity"] = s.particle_porosity;
        values["density"] = s.density;
        values["substrate_top"] = s.substrate_top;
        values["bond_radius_ratio"] = s.bond_radius_ratio;
        values["lattice_commensurate"] = s.lattice_commensurate;
        values["seconds"] = s.seconds;
        return namespace_of(values);
      },
      py::arg("packing"), py::kw_only(), py::arg("pores") = "fcc", py::arg("pore_diameter") = 0.0,
      py::arg("pore_ratio") = 0.0, py::arg("orientation") = "111", py::arg("pore_spacing") = 1.0,
      py::arg("pore_origin") = py::none(), py::arg("pore_count") = 0, py::arg("pore_fraction") = 0.0,
      py::arg("pore_centres") = py::none(), py::arg("pore_radii") = py::none(), py::arg("coating") = 0.0,
      py::arg("opening_distance_ratio") = 1.0, py::arg("substrate_layers") = 2.0, py::arg("bond_cutoff") = 1.75,
      py::arg("bond_radius_ratio") = 1.0, py::arg("silica_density") = 1297.0, py::arg("titania_density") = 3660.0,
      py::arg("seed") = 1, py::arg("threads") = 1, R"doc(
`packlab build opal`: inverse-opal bonded-particle model (docs/opal-build.md). pores: "fcc",
"random" or "list" (pore_centres N x 3 and pore_radii N [m]); pore_diameter [m] or pore_ratio
(to the mean particle diameter); orientation "111" | "100"; pore_spacing (nearest-neighbour
distance / D); pore_origin (x, y, z) [m]; pore_count or pore_fraction (random); coating L_coat
[m]; opening_distance_ratio; substrate_layers; bond_cutoff (x (r_i + r_j)); bond_radius_ratio;
silica_density, titania_density [kg/m^3]; seed; threads. Returns a namespace: packing (types
0 silica, 3 titania, 4 substrate; fixed; bonds with material 0 silica, 1 titania, 2 substrate),
pore_centres, pore_radii and the report's figures (particles, bonds, mean_coordination,
porosity, density, ...).
)doc");
}

}  // namespace packlab::python
