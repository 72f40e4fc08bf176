// packlab build opal IN [--config FILE.toml] --pores fcc|random (--pore-diameter D | --pore-ratio Q) [--orientation
// 111|100]
//   [--pore-spacing 1] [--pore-origin X,Y,Z] [--pore-count N | --pore-fraction F] [--coating T]
//   [--opening-distance-ratio 1] [--substrate-layers 2] [--bond-cutoff 1.75] [--bond-radius-ratio 1]
//   [--silica-density 1297] [--titania-density 3660] [--seed S] [--threads T] --out DIR
// Inverse-opal bonded-particle model (generate/opal.hpp, bpm-inverse-opals §2.1): pores cut out
// of a particle packing (eq. 1), optional titania coating shell (eq. 2) with free interpore
// openings, fixed substrate of the bottom layers, bonds within the cutoff across periodic
// boundaries. Writes DIR/opal.vtu (the bonded model: types, fixed flags, bonds with material,
// image and rest length), DIR/pores.xyz (the pore set as spheres), DIR/profile.csv (particles
// per type along z) and report.json.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/core/error.hpp"
#include "packlab/generate/opal.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

void add_build_opal(CLI::App& build) {
  add_option_command(
      build, "opal",
      "Inverse-opal bonded-particle model: pores (FCC or random), coating, fixed substrate, bonds "
      "(bpm-inverse-opals §2.1)",
      io::opal_build_options,
      {.input = "Input particle packing (any readable format; e.g. from generate fba)", .output = "Output folder"},
      [](const OptionCommand<io::OpalBuildOptions>& c) {
        const auto t0 = std::chrono::steady_clock::now();
        const Packing in = io::read_packing(c.in);
        nlohmann::json pore_params;
        const generate::OpalOptions o = c.settings.resolve(in, &pore_params);
        const double D = pore_params["diameter_m"].get<double>();
        double mean_d = 0;  // the profile's slab thickness
        for (double r : in.radius) mean_d += 2.0 * r;
        mean_d /= static_cast<double>(in.size());
        const io::OutputFolder folder(c.out);  // removed again on an error before any output
        generate::OpalSummary s;
        const Packing model = generate::build_opal(in, o, &s, [&](const std::string& phase, double) {
          if (!c.quiet && phase != "done") fmt::print(stderr, "build opal: {}\n", phase);
        });
        const generate::PoreSet pores = generate::opal_pores(in, o);
        const std::filesystem::path dir(c.out);
        io::WriteOptions w;
        w.comment = fmt::format(
            "packlab {} build opal {} pores={} D={:g} coating={:g} bond_cutoff={:g} "
            "bond_radius_ratio={:g}",
            io::version(), c.in, c.settings.pores, D, o.coating_thickness, o.bond_cutoff_ratio, o.bond_radius_ratio);
        io::write_packing(model, dir / "opal.vtu", w);
        Packing pore_packing;
        pore_packing.box = in.box;
        for (std::size_t k = 0; k < pores.size(); ++k)
          pore_packing.add(pores.centre[k], pores.radius[k], particle_type::pore);
        io::write_packing(pore_packing, dir / "pores.xyz", w);
        // Profile along z: particles per type in slabs of one mean diameter.
        {
          const double zlo = in.box.lo.z, h = mean_d;
          const int bins = std::max(1, static_cast<int>(std::ceil(in.box.length.z / h)));
          std::vector<std::array<long, 3>> count(static_cast<std::size_t>(bins), {0, 0, 0});
          for (std::size_t i = 0; i < model.size(); ++i) {
            const int b = std::clamp(static_cast<int>((model.position[i].z - zlo) / h), 0, bins - 1);
            const int t = model.type[i] == particle_type::coating     ? 1
                          : model.type[i] == particle_type::substrate ? 2
                                                                      : 0;
            ++count[static_cast<std::size_t>(b)][static_cast<std::size_t>(t)];
          }
          std::ostringstream csv;
          csv << "z_m,silica,titania,substrate\n";
          for (int b = 0; b < bins; ++b)
            csv << fmt::format("{:.8g},{},{},{}\n", zlo + (b + 0.5) * h, count[static_cast<std::size_t>(b)][0],
                               count[static_cast<std::size_t>(b)][1], count[static_cast<std::size_t>(b)][2]);
          io::write_text_atomically(dir / "profile.csv", csv.str());
        }
        nlohmann::json report = io::report_header("build opal");
        report["parameters"] = {{"input", c.in},
                                {"pores", pore_params},
                                {"coating_thickness_m", o.coating_thickness},
                                {"opening_distance_ratio", o.opening_distance_ratio},
                                {"substrate_layers", o.substrate_layers},
                                {"bond_cutoff_ratio", o.bond_cutoff_ratio},
                                {"bond_radius_ratio", o.bond_radius_ratio},
                                {"silica_density_kg_m3", o.silica_density},
                                {"titania_density_kg_m3", o.titania_density},
                                {"threads", o.threads}};
        report["results"] = {
            {"input_particles", s.input_particles},
            {"particles", s.particles},
            {"silica_particles", s.structural},
            {"titania_particles", s.coating},
            {"substrate_particles", s.substrate},
            {"removed_particles", s.removed},
            {"coating_dropped_at_openings", s.coating_openings},
            {"pores", s.pores},
            {"bonds", s.bonds},
            {"bonds_silica", s.bonds_by_material[0]},
            {"bonds_titania", s.bonds_by_material[1]},
            {"bonds_substrate", s.bonds_by_material[2]},
            {"bond_materials", {{"0", "silica"}, {"1", "titania"}, {"2", "substrate"}}},
            {"periodic_bonds", s.periodic_bonds},
            {"mean_coordination", s.mean_coordination},
            {"bonds_per_particle", s.particles ? static_cast<double>(s.bonds) / static_cast<double>(s.particles) : 0.0},
            {"porosity", s.porosity},
            {"particle_porosity", s.particle_porosity},
            {"density_kg_m3", s.density},
            {"mean_particle_diameter_m", s.mean_particle_diameter},
            {"substrate_top_m", s.substrate_top},
            {"lattice_commensurate", s.lattice_commensurate},
            {"build_seconds", s.seconds}};
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        report["seconds"] = seconds;
        io::write_report(dir / "report.json", report);
        if (!s.lattice_commensurate)
          fmt::print(
              stderr,
              "packlab: warning: the FCC pore lattice (period {:g} x {:g} x {:g} m) does not fit the periodic box: "
              "pores form a seam at the boundary\n",
              generate::fcc_pore_period(o.fcc).x, generate::fcc_pore_period(o.fcc).y,
              generate::fcc_pore_period(o.fcc).z);
        if (!c.quiet)
          fmt::print(
              "{} particles ({} silica, {} titania, {} substrate), {} bonds, mean coordination {:.3f}, porosity "
              "{:.4f}, density {:.1f} kg/m^3, {} pores; wrote {} in {:.2f} s\n",
              s.particles, s.structural, s.coating, s.substrate, s.bonds, s.mean_coordination, s.porosity, s.density,
              s.pores, c.out, seconds);
      });
}

}  // namespace packlab::cli
