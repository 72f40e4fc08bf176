#include "packlab/mechanics/compression_test.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

#include "packlab/core/error.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"

namespace packlab::mechanics {

std::vector<dem::Material> opal_particle_types(const OpalMaterials& m) {
  dem::Material silica;
  silica.youngs_modulus = m.silica_youngs_modulus;
  silica.poisson_ratio = m.silica_poisson_ratio;
  silica.density = m.silica_density;
  silica.restitution = m.restitution;
  silica.friction = m.friction;
  silica.rolling_friction = m.rolling_friction;
  silica.damping = m.damping;
  dem::Material titania = silica;
  titania.youngs_modulus = m.titania_youngs_modulus;
  titania.poisson_ratio = m.titania_poisson_ratio;
  titania.density = m.titania_density;
  std::vector<dem::Material> types(5, silica);
  types[static_cast<std::size_t>(particle_type::coating)] = titania;
  return types;
}

std::vector<dem::ElasticBond::Params> opal_bond_materials(const OpalMaterials& m) {
  dem::ElasticBond::Params silica{m.silica_youngs_modulus, m.silica_poisson_ratio, m.silica_strength,
                                  m.silica_strength, m.bond_radius_ratio, m.relaxation_time};
  dem::ElasticBond::Params titania{m.titania_youngs_modulus, m.titania_poisson_ratio, m.titania_strength,
                                   m.titania_strength, m.bond_radius_ratio, m.relaxation_time};
  silica.compressive_breakage = titania.compressive_breakage = m.compressive_breakage;
  return {silica, titania, silica};
}

void CompressionOptions::validate() const {
  require(strain_rate > 0.0 && std::isfinite(strain_rate), "strain_rate", strain_rate, "> 0 1/s");
  require(max_strain > 0.0 && max_strain < 0.5, "max_strain", max_strain, "in (0, 0.5)");
  require(stop_drop >= 0.0 && stop_drop < 1.0, "stop_drop", stop_drop, "in [0, 1) (0 = run to max_strain)");
  if (sides != "periodic" && sides != "open") fail_input(fmt::format("sides = {}: must be 'periodic' or 'open'", sides));
  if (plate != "glued" && plate != "contact") fail_input(fmt::format("plate = {}: must be 'glued' or 'contact'", plate));
  require(plate_layers > 0.0 && plate_layers <= 100.0, "plate_layers", plate_layers, "in (0, 100]");
  require(substrate_layers >= 0.0 && substrate_layers <= 100.0, "substrate_layers", substrate_layers, "in [0, 100]");
  require(time_step >= 0.0 && std::isfinite(time_step), "time_step", time_step, ">= 0 s (0 = automatic)");
  require(time_step_safety > 0.0 && time_step_safety <= 1.0, "time_step_safety", time_step_safety, "in (0, 1]");
  require(samples >= 10 && samples <= 10000000, "samples", static_cast<double>(samples), "in [10, 1e7]");
  require(modulus_lower >= 0.0 && modulus_lower < 1.0, "modulus_lower", modulus_lower, "in [0, 1)");
  require(modulus_window > 0.0 && modulus_window <= 1.0, "modulus_window", modulus_window, "in (0, 1]");
  require(threads >= 0, "threads", threads, ">= 0 (0 = all cores)");
  for (double s : snapshot_strains)
    require(s > 0.0 && s <= max_strain, "snapshot strain", s, "in (0, max_strain]");
  if (types.empty()) fail_input("compression test: no particle type parameters given");
  if (bond_materials.empty()) fail_input("compression test: no bond material parameters given");
}

void CompressionSetup::finish(const Packing& model) {
  require(strain_rate >= 0.0 && std::isfinite(strain_rate), "strain_rate", strain_rate, ">= 0 1/s (0 = automatic)");
  require(quasi_static > 0.0 && quasi_static <= 0.1, "quasi_static", quasi_static, "in (0, 0.1]");
  options.types = opal_particle_types(materials);
  options.bond_materials = opal_bond_materials(materials);
  options.snapshot_strains = snapshot_strains;
  if (strain_rate > 0.0) {
    options.strain_rate = strain_rate;
    return;
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t k = 0; k < model.size(); ++k) {
    lo = std::min(lo, model.position[k].z - model.radius[k]);
    hi = std::max(hi, model.position[k].z + model.radius[k]);
  }
  if (!(hi > lo)) fail_input("compression test: the model has no height");
  const double c = std::sqrt(materials.silica_youngs_modulus / materials.silica_density);
  options.strain_rate = quasi_static * c / (hi - lo);
}

ModulusFit fit_youngs_modulus(const std::vector<double>& strain, const std::vector<double>& stress,
                              double lower_fraction, double window_fraction) {
  ModulusFit fit;
  const std::size_t n = std::min(strain.size(), stress.size());
  if (n < 3) return fit;
  std::size_t peak = 0;
  for (std::size_t k = 1; k < n; ++k)
    if (stress[k] > stress[peak]) peak = k;
  const double smax = stress[peak];
  if (!(smax > 0.0)) return fit;
  const double lower = lower_fraction * smax, width = window_fraction * smax;
  for (std::size_t a = 0; a <= peak; ++a) {
    if (stress[a] < lower) continue;
    // The window: points a..b with stress[b] - stress[a] spanning `width` (monotone enough).
    std::size_t b = a;
    while (b < peak && stress[b] - stress[a] < width) ++b;
    if (stress[b] - stress[a] < width) break;  // the rest of the curve spans less than a window
    const std::size_t m = b - a + 1;
    if (m < 3) continue;
    double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    for (std::size_t k = a; k <= b; ++k) {
      sx += strain[k];
      sy += stress[k];
      sxx += strain[k] * strain[k];
      sxy += strain[k] * stress[k];
      syy += stress[k] * stress[k];
    }
    const double dm = static_cast<double>(m);
    const double vx = sxx - sx * sx / dm, vxy = sxy - sx * sy / dm, vy = syy - sy * sy / dm;
    if (!(vx > 0.0)) continue;
    const double slope = vxy / vx;
    if (!fit.found || slope > fit.youngs_modulus) {
      fit.found = true;
      fit.youngs_modulus = slope;
      fit.intercept = (sy - slope * sx) / dm;
      fit.strain_begin = strain[a];
      fit.strain_end = strain[b];
      fit.points = static_cast<int>(m);
      fit.r2 = vy > 0.0 ? vxy * vxy / (vx * vy) : 1.0;
    }
  }
  return fit;
}

std::vector<TypeStress> stress_by_type(const Packing& model, const std::vector<std::array<double, 9>>& stress) {
  int types = 0;
  for (int t : model.type) types = std::max(types, t + 1);
  std::vector<TypeStress> out(static_cast<std::size_t>(types));
  std::vector<std::array<double, 3>> sum(out.size(), std::array<double, 3>{}), sum2(out.size(), std::array<double, 3>{});
  for (std::size_t k = 0; k < model.size() && k < stress.size(); ++k) {
    if (!model.fixed.empty() && model.fixed[k]) continue;
    const auto t = static_cast<std::size_t>(model.type[k]);
    ++out[t].particles;
    for (int a = 0; a < 3; ++a) {
      const double s = stress[k][static_cast<std::size_t>(4 * a)];
      sum[t][static_cast<std::size_t>(a)] += s;
      sum2[t][static_cast<std::size_t>(a)] += s * s;
    }
  }
  std::vector<TypeStress> kept;
  for (std::size_t t = 0; t < out.size(); ++t) {
    out[t].type = static_cast<int>(t);
    if (out[t].particles == 0) continue;
    const double n = static_cast<double>(out[t].particles);
    for (std::size_t a = 0; a < 3; ++a) {
      out[t].mean[a] = sum[t][a] / n;
      out[t].sd[a] = n > 1 ? std::sqrt(std::max(0.0, (sum2[t][a] - n * out[t].mean[a] * out[t].mean[a]) / (n - 1))) : 0.0;
    }
    kept.push_back(out[t]);
  }
  return kept;
}

std::vector<std::size_t> histogram(const std::vector<double>& values, double lo, double hi, int bins) {
  std::vector<std::size_t> counts(static_cast<std::size_t>(std::max(bins, 1)), 0);
  if (!(hi > lo)) return counts;
  for (double v : values) {
    if (!std::isfinite(v) || v < lo || v > hi) continue;
    auto k = static_cast<long>((v - lo) / (hi - lo) * bins);
    k = std::clamp(k, 0L, static_cast<long>(bins) - 1);
    ++counts[static_cast<std::size_t>(k)];
  }
  return counts;
}

CompressionResult run_compression(const Packing& bonded_model, const CompressionOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  options.validate();
  bonded_model.validate();
  if (bonded_model.size() == 0) fail_input("compression test: the model has no particles");
  if (bonded_model.bonds.empty())
    fail_input("compression test: the model has no bonds (make them with `packlab bond IN --model beam`)");

  CompressionResult result;
  Packing model = bonded_model;
  model.velocity.clear();
  model.angular_velocity.clear();
  // Open z, and x, y for open sides; drop the bonds across an opened boundary.
  std::array<bool, 3> open_axis{options.sides == "open", options.sides == "open", true};
  for (int a = 0; a < 3; ++a)
    if (open_axis[static_cast<std::size_t>(a)]) model.box.periodic[static_cast<std::size_t>(a)] = false;
  const std::size_t n = model.size();
  // Substrate.
  bool any_fixed = false;
  for (auto f : model.fixed) any_fixed = any_fixed || f;
  double zmin = std::numeric_limits<double>::infinity(), bottom = zmin, top = -zmin, dsum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    zmin = std::min(zmin, model.position[k].z);
    bottom = std::min(bottom, model.position[k].z - model.radius[k]);
    top = std::max(top, model.position[k].z + model.radius[k]);
    dsum += 2.0 * model.radius[k];
  }
  if (!any_fixed) {
    if (!(options.substrate_layers > 0.0))
      fail_input("substrate_layers = 0: the model has no fixed particles, so at least one substrate layer must be fixed");
    const double cut = zmin + (options.substrate_layers - 0.5) * dsum / static_cast<double>(n);
    model.fixed.assign(n, 0);
    for (std::size_t k = 0; k < n; ++k) model.fixed[k] = model.position[k].z < cut ? 1 : 0;
  }
  if (model.fixed.empty()) model.fixed.assign(n, 0);
  for (auto f : model.fixed) result.fixed_particles += f ? 1 : 0;
  // Glued plate: the top layers become fixed particles driven with the plate.
  const bool glued = options.plate == "glued";
  std::vector<std::uint8_t> grip(n, 0);
  double substrate_top = -std::numeric_limits<double>::infinity(), grip_bottom = -substrate_top, zmax = substrate_top;
  for (std::size_t k = 0; k < n; ++k) {
    zmax = std::max(zmax, model.position[k].z);
    if (model.fixed[k]) substrate_top = std::max(substrate_top, model.position[k].z);
  }
  if (glued) {
    const double cut = zmax - (options.plate_layers - 0.5) * dsum / static_cast<double>(n);
    for (std::size_t k = 0; k < n; ++k)
      if (!model.fixed[k] && model.position[k].z > cut) {
        grip[k] = 1;
        model.fixed[k] = 1;
        grip_bottom = std::min(grip_bottom, model.position[k].z);
        ++result.glued_particles;
      }
    if (result.glued_particles == 0 || !(grip_bottom > substrate_top))
      fail_input("compression test: the glued plate layers and the substrate meet (sample too thin for "
                 "plate_layers + substrate_layers)");
  }
  if (result.fixed_particles == 0 || result.fixed_particles + result.glued_particles >= n)
    fail_input(fmt::format("compression test: {} of {} particles are fixed; the substrate must hold some but not all",
                           result.fixed_particles, n));
  {
    Bonds kept;
    const Bonds& in = model.bonds;
    for (std::size_t b = 0; b < in.size(); ++b) {
      bool drop = in.state[b] != 0;
      for (std::size_t a = 0; a < 3; ++a) drop = drop || (open_axis[a] && in.image[b][a] != 0);
      drop = drop || (model.fixed[static_cast<std::size_t>(in.i[b])] && model.fixed[static_cast<std::size_t>(in.j[b])]);
      if (drop) {
        ++result.dropped_bonds;
        continue;
      }
      kept.add(in.i[b], in.j[b], in.image[b], in.material[b], in.rest_length[b], 0);
    }
    model.bonds = std::move(kept);
  }
  if (model.bonds.empty()) fail_input("compression test: no load-bearing bonds left (all between fixed particles or across opened boundaries)");
  result.bonds = model.bonds.size();
  result.particles = n;

  // Cross-section and height.
  if (options.sides == "periodic" && model.box.periodic[0] && model.box.periodic[1]) {
    result.area = model.box.length.x * model.box.length.y;
  } else {
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3& p = model.position[k];
      const double r = model.radius[k];
      if (model.box.periodic[0]) {
        x0 = model.box.lo.x;
        x1 = model.box.lo.x + model.box.length.x;
      } else {
        x0 = std::min(x0, p.x - r);
        x1 = std::max(x1, p.x + r);
      }
      if (model.box.periodic[1]) {
        y0 = model.box.lo.y;
        y1 = model.box.lo.y + model.box.length.y;
      } else {
        y0 = std::min(y0, p.y - r);
        y1 = std::max(y1, p.y + r);
      }
    }
    result.area = (x1 - x0) * (y1 - y0);
  }
  result.height = glued ? grip_bottom - substrate_top : top - bottom;

  dem::EngineConfig config;
  config.contact_law = "hertz_mindlin";
  config.types = options.types;
  config.bond_materials = options.bond_materials;
  config.time_step = options.time_step;
  config.time_step_safety = options.time_step_safety;
  config.threads = options.threads;
  dem::Engine engine(model, config);
  const double dt = engine.time_step();
  result.time_step = dt;
  result.plate_speed = options.strain_rate * result.height;
  // Contact plate: a wall. Glued plate: the grip particles move with it (and a wall above them
  // keeps nothing else from passing; it touches nothing).
  const std::size_t plate = engine.add_wall(dem::Wall{{0.0, 0.0, top}, {0.0, 0.0, -1.0}, {0.0, 0.0, -result.plate_speed}});
  std::vector<std::size_t> grip_internal;
  if (glued) {
    for (std::size_t k = 0; k < n; ++k)
      if (grip[static_cast<std::size_t>(engine.original_index()[k])]) {
        grip_internal.push_back(k);
        engine.particles().velocity[k] = Vec3{0.0, 0.0, -result.plate_speed};
      }
  }
  auto plate_force = [&] {
    if (!glued) return engine.wall_force(plate).z;
    double f = 0.0;
    for (std::size_t k : grip_internal) f += engine.particles().force[k].z;
    return f;
  };

  const double total_time = options.max_strain / options.strain_rate;
  const auto total_steps = static_cast<long>(std::ceil(total_time / dt));
  const long interval = std::max(1L, total_steps / options.samples);
  std::vector<double> pending = options.snapshot_strains;
  std::sort(pending.begin(), pending.end());
  std::size_t next_snapshot = 0;
  double peak = 0.0;
  result.stop_reason = "reached max_strain";
  const double t_start = engine.time();
  while (engine.step_count() < total_steps) {
    const long remaining = total_steps - engine.step_count();
    const long chunk = std::min(interval, remaining);
    if (chunk > 1) engine.run(chunk - 1);
    const dem::Diagnostics d = engine.step_measured();
    CompressionPoint p;
    p.step = d.step;
    p.time = d.time - t_start;
    p.displacement = result.plate_speed * p.time;
    p.strain = p.displacement / result.height;
    p.force = plate_force();
    p.stress = p.force / result.area;
    p.kinetic_energy = d.kinetic_energy;
    p.strain_energy = d.strain_energy;
    p.broken_bonds = d.broken_bonds;
    result.curve.push_back(p);
    if (options.on_point) options.on_point(p);
    if (p.stress > peak) {
      peak = p.stress;
      result.strain_at_peak = p.strain;
    }
    while (next_snapshot < pending.size() && p.strain >= pending[next_snapshot]) {
      CompressionSnapshot s;
      s.requested_strain = pending[next_snapshot++];
      s.strain = p.strain;
      s.stress = p.stress;
      s.bond_strain = engine.bond_strains();
      s.particle_stress = dem::particle_stress(engine.contact_forces(), engine.packing());
      result.snapshots.push_back(std::move(s));
    }
    if (options.stop_drop > 0.0 && peak > 0.0 && p.strain > result.strain_at_peak && p.stress < options.stop_drop * peak &&
        d.broken_bonds > 0) {
      result.stop_reason = fmt::format("stress fell below {:g} x peak after the peak", options.stop_drop);
      break;
    }
  }
  result.steps = engine.step_count();
  result.strength = peak;
  std::vector<double> strain, stress;
  for (const auto& p : result.curve) {
    strain.push_back(p.strain);
    stress.push_back(p.stress);
  }
  result.modulus = fit_youngs_modulus(strain, stress, options.modulus_lower, options.modulus_window);
  result.youngs_modulus = result.modulus.youngs_modulus;
  for (const auto& p : result.curve)
    if (p.stress > 0.2 * peak && p.strain <= result.strain_at_peak && p.strain_energy > 0.0)
      result.max_kinetic_ratio = std::max(result.max_kinetic_ratio, p.kinetic_energy / p.strain_energy);
  result.breaks = engine.bond_breaks();
  result.broken_bonds = result.breaks.size();
  result.model = engine.packing();  // fixed = substrate and glued plate layers
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace packlab::mechanics

namespace packlab::mechanics {

nlohmann::json compression_report(const CompressionResult& r, const CompressionOptions& o) {
  nlohmann::json j;
  j["youngs_modulus"] = r.youngs_modulus;
  j["strength"] = r.strength;
  j["broken_bonds"] = r.broken_bonds;
  j["strain_at_peak"] = r.strain_at_peak;
  j["modulus_fit"] = {{"method", "max_tangent"},
                      {"lower_fraction", o.modulus_lower},
                      {"window_fraction", o.modulus_window},
                      {"strain_begin", r.modulus.strain_begin},
                      {"strain_end", r.modulus.strain_end},
                      {"points", r.modulus.points},
                      {"r2", r.modulus.r2},
                      {"found", r.modulus.found}};
  j["height"] = r.height;
  j["area"] = r.area;
  j["plate_speed"] = r.plate_speed;
  j["strain_rate"] = o.strain_rate;
  j["max_strain"] = o.max_strain;
  j["sides"] = o.sides;
  j["plate"] = o.plate;
  j["plate_layers"] = o.plate_layers;
  j["glued_particles"] = r.glued_particles;
  j["time_step"] = r.time_step;
  j["steps"] = r.steps;
  j["max_kinetic_to_strain_energy"] = r.max_kinetic_ratio;
  j["particles"] = r.particles;
  j["fixed_particles"] = r.fixed_particles;
  j["bonds"] = r.bonds;
  j["dropped_bonds"] = r.dropped_bonds;
  j["stop_reason"] = r.stop_reason;
  j["seconds"] = r.seconds;
  j["particle_steps_per_second"] =
      r.seconds > 0 ? static_cast<double>(r.particles) * static_cast<double>(r.steps) / r.seconds : 0.0;
  j["bond_steps_per_second"] =
      r.seconds > 0 ? static_cast<double>(r.bonds) * static_cast<double>(r.steps) / r.seconds : 0.0;
  nlohmann::json snaps = nlohmann::json::array();
  for (const auto& s : r.snapshots) {
    nlohmann::json sj{{"requested_strain", s.requested_strain}, {"strain", s.strain}, {"stress", s.stress}};
    nlohmann::json types = nlohmann::json::array();
    for (const auto& t : stress_by_type(r.model, s.particle_stress))
      types.push_back({{"type", t.type},
                       {"particles", t.particles},
                       {"mean_xx", t.mean[0]}, {"mean_yy", t.mean[1]}, {"mean_zz", t.mean[2]},
                       {"sd_xx", t.sd[0]}, {"sd_yy", t.sd[1]}, {"sd_zz", t.sd[2]},
                       {"axial_to_vertical", t.mean[2] != 0.0 ? t.mean[0] / t.mean[2] : 0.0}});
    sj["stress_by_type"] = types;
    double lo = 0, hi = 0, sum = 0;
    std::size_t count = 0, compressed = 0;
    for (double e : s.bond_strain)
      if (std::isfinite(e)) {
        lo = std::min(lo, e);
        hi = std::max(hi, e);
        sum += e;
        ++count;
        compressed += e < 0.0;
      }
    sj["bond_strain"] = {{"min", lo}, {"max", hi}, {"mean", count ? sum / static_cast<double>(count) : 0.0},
                         {"compressed_fraction", count ? static_cast<double>(compressed) / static_cast<double>(count) : 0.0}};
    snaps.push_back(sj);
  }
  j["snapshots"] = snaps;
  j["units"] = {{"youngs_modulus", "Pa"}, {"strength", "Pa"}, {"height", "m"}, {"area", "m^2"},
                {"plate_speed", "m/s"}, {"strain_rate", "1/s"}, {"time_step", "s"}, {"stress", "Pa"}};
  return j;
}

void write_compression_outputs(const CompressionResult& r, const CompressionOptions& /*o*/, const std::filesystem::path& dir,
                               bool plots, bool write_model) {
  std::filesystem::create_directories(dir);
  io::PlotOptions plot;
  plot.enabled = plots;
  {
    std::string csv = "step,time,displacement,strain,force,stress,kinetic_energy,strain_energy,broken_bonds\n";
    for (const auto& p : r.curve)
      csv += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{}\n", p.step, p.time,
                         p.displacement, p.strain, p.force, p.stress, p.kinetic_energy, p.strain_energy, p.broken_bonds);
    io::write_text_atomically(dir / "curve.csv", csv);
    const std::string curve = (dir / "curve.csv").string();
    io::make_plot("stress_strain",
                  {curve, "--modulus", fmt::format("{:.17g}", r.modulus.youngs_modulus), "--intercept",
                   fmt::format("{:.17g}", r.modulus.intercept), "--fit-begin", fmt::format("{:.17g}", r.modulus.strain_begin),
                   "--fit-end", fmt::format("{:.17g}", r.modulus.strain_end)},
                  dir / "stress_strain.png", plot);
    io::make_plot("stress_strain", {curve, "--force-displacement"}, dir / "force_displacement.png", plot);
    io::make_plot("broken_bonds", {curve}, dir / "broken_bonds.png", plot);
  }
  if (!r.snapshots.empty()) {
    double lo = 0, hi = 0;
    for (const auto& s : r.snapshots)
      for (double e : s.bond_strain)
        if (std::isfinite(e)) {
          lo = std::min(lo, e);
          hi = std::max(hi, e);
        }
    const int bins = 60;
    if (!(hi > lo)) hi = lo + 1e-6;
    std::string csv = "strain_bin";
    for (const auto& s : r.snapshots) csv += fmt::format(",fraction_at_{:.6g}", s.strain);
    csv += "\n";
    std::vector<std::vector<std::size_t>> h;
    std::vector<double> totals;
    for (const auto& s : r.snapshots) {
      h.push_back(histogram(s.bond_strain, lo, hi, bins));
      double t = 0;
      for (auto c : h.back()) t += static_cast<double>(c);
      totals.push_back(t > 0 ? t : 1.0);
    }
    for (int b = 0; b < bins; ++b) {
      csv += fmt::format("{:.17g}", lo + (b + 0.5) * (hi - lo) / bins);
      for (std::size_t s = 0; s < h.size(); ++s)
        csv += fmt::format(",{:.17g}", static_cast<double>(h[s][static_cast<std::size_t>(b)]) / totals[s]);
      csv += "\n";
    }
    io::write_text_atomically(dir / "bond_strain.csv", csv);
    io::make_plot("bond_strain", {(dir / "bond_strain.csv").string()}, dir / "bond_strain.png", plot);
    std::string ps = "strain,stress,type,particles,mean_xx,sd_xx,mean_yy,sd_yy,mean_zz,sd_zz\n";
    for (const auto& s : r.snapshots)
      for (const auto& t : stress_by_type(r.model, s.particle_stress))
        ps += fmt::format("{:.17g},{:.17g},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", s.strain, s.stress,
                          t.type, t.particles, t.mean[0], t.sd[0], t.mean[1], t.sd[1], t.mean[2], t.sd[2]);
    io::write_text_atomically(dir / "particle_stress.csv", ps);
  }
  {
    std::string csv = "bond,time,strain,x,y,z\n";
    Packing breaks;
    breaks.box = r.model.box;
    auto& time_field = breaks.field_or_add("time");
    std::vector<double> times, strains;
    for (const auto& b : r.breaks) {
      const double strain = r.plate_speed * b.time / r.height;
      csv += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", b.bond, b.time, strain, b.position.x,
                         b.position.y, b.position.z);
      const auto& bonds = r.model.bonds;
      const double rb = 0.5 * std::min(r.model.radius[static_cast<std::size_t>(bonds.i[b.bond])],
                                       r.model.radius[static_cast<std::size_t>(bonds.j[b.bond])]);
      breaks.add(b.position, rb, 0);
      times.push_back(b.time);
      strains.push_back(strain);
    }
    time_field.values = times;
    breaks.field_or_add("strain").values = strains;
    io::write_text_atomically(dir / "broken_bonds.csv", csv);
    io::WriteOptions w;
    w.comment = "packlab test compress: positions of failed bonds (bond midpoints at failure)";
    io::write_packing(breaks, dir / "broken_bonds.vtu", w);
  }
  if (write_model) {
    io::WriteOptions w;
    w.comment = "packlab test compress: final state (bond state 1 = broken)";
    io::write_packing(r.model, dir / "model.vtu", w);
  }
}

}  // namespace packlab::mechanics
