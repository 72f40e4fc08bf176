// Uniaxial compression: the loading protocol (plate, curve points, snapshots, stop rule) and
// the result's columns. The specimen: uniaxial_compression_setup.cpp.
#include "packlab/mechanics/uniaxial_compression.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/mechanics/row_columns.hpp"
#include "packlab/mechanics/static_loading.hpp"

namespace packlab::mechanics {

Columns curve_columns(const std::vector<UniaxialCompressionPoint>& curve) {
  using P = UniaxialCompressionPoint;
  Columns t;
  add_row_column(
      t, "step", curve, [](const P& p) { return p.step; }, Column::Kind::integer);
  add_real_row_columns(t, curve,
                       {{"time", &P::time},
                        {"displacement", &P::displacement},
                        {"strain", &P::strain},
                        {"force", &P::force},
                        {"stress", &P::stress},
                        {"kinetic_energy", &P::kinetic_energy},
                        {"strain_energy", &P::strain_energy}});
  add_row_column(
      t, "broken_bonds", curve, [](const P& p) { return p.broken_bonds; }, Column::Kind::integer);
  return t;
}

namespace {

// The adaptive rate's phase (options.elastic_speedup > 1): whether the plate still moves fast,
// the plate's displacement at the end of the last fast step (from the switch on: at the switch,
// where the constant rate takes over), and the switch's step and time since the start of the test.
struct RatePhase {
  bool fast = false;
  double displacement = 0.0;  // [m]
  long switch_step = 0;
  double switch_time = 0.0;  // [s]
};

// The state written by run_uniaxial_compression's `save` (options.checkpoint).
void load_compression_state(std::istream& in, dem::Engine& engine, bool& stopped, double& peak,
                            UniaxialCompressionResult& result, RatePhase* phase) {
  engine.load_state(in);
  std::uint8_t stop = 0;
  binary::read(in, stop, "stop flag");
  binary::read_string(in, result.stop_reason, "stop reason");
  binary::read(in, peak, "peak stress");
  binary::read(in, result.strain_at_peak, "strain at the peak");
  binary::read_vector(in, result.curve, "curve");
  if (stop > 1) fail_input("checkpoint is damaged: compression state");
  stopped = stop == 1;
  read_compression_snapshots(in, result.snapshots);
  if (phase != nullptr) {  // written only with elastic_speedup > 1: older checkpoints still load
    std::uint8_t fast = 0;
    binary::read(in, fast, "rate phase");
    if (fast > 1) fail_input("checkpoint is damaged: rate phase");
    phase->fast = fast == 1;
    binary::read(in, phase->displacement, "plate displacement");
    binary::read(in, phase->switch_step, "rate switch step");
    binary::read(in, phase->switch_time, "rate switch time");
    binary::read(in, result.rolled_back_steps, "rolled back steps");
  }
}

}  // namespace

void write_compression_snapshots(std::ostream& out, const std::vector<UniaxialCompressionSnapshot>& snapshots) {
  binary::write(out, static_cast<std::uint64_t>(snapshots.size()));
  for (const UniaxialCompressionSnapshot& s : snapshots) {
    binary::write(out, std::array<double, 3>{s.requested_strain, s.strain, s.stress});
    binary::write_vector(out, s.bond_strain);
    binary::write_vector(out, s.particle_stress);
  }
}

void read_compression_snapshots(std::istream& in, std::vector<UniaxialCompressionSnapshot>& snapshots) {
  std::uint64_t count = 0;
  binary::read(in, count, "snapshot count");
  if (count > (1U << 16)) fail_input("checkpoint is damaged: snapshot count");
  snapshots.resize(count);
  for (UniaxialCompressionSnapshot& s : snapshots) {
    std::array<double, 3> values{};
    binary::read(in, values, "snapshot");
    s.requested_strain = values[0];
    s.strain = values[1];
    s.stress = values[2];
    binary::read_vector(in, s.bond_strain, "snapshot bond strains");
    binary::read_vector(in, s.particle_stress, "snapshot particle stresses");
  }
}

PendingSnapshots::PendingSnapshots(const UniaxialCompressionOptions& options)
    : strains(options.snapshot_strains), stresses(options.snapshot_stresses) {
  std::sort(strains.begin(), strains.end());
  std::sort(stresses.begin(), stresses.end());
}

UniaxialCompressionSnapshot PendingSnapshots::take_strain() {
  UniaxialCompressionSnapshot s;
  s.requested_strain = strains[next_strain++];
  return s;
}

UniaxialCompressionSnapshot PendingSnapshots::take_stress() {
  UniaxialCompressionSnapshot s;
  s.requested_strain = std::numeric_limits<double>::quiet_NaN();
  s.requested_stress = stresses[next_stress++];
  return s;
}

void PendingSnapshots::resume(std::vector<UniaxialCompressionSnapshot>& taken) {
  next_strain = next_stress = 0;
  for (UniaxialCompressionSnapshot& s : taken) {
    if (std::isnan(s.requested_strain)) {
      if (next_stress >= stresses.size()) fail_input("checkpoint is damaged: more snapshots than snapshot_stresses");
      s.requested_stress = stresses[next_stress++];
    } else {
      if (next_strain >= strains.size() || s.requested_strain != strains[next_strain])
        fail_input("checkpoint is damaged: a snapshot of a strain not in snapshot_strains");
      ++next_strain;
    }
  }
}

dem::EngineConfig compression_engine_config(const UniaxialCompressionOptions& options) {
  dem::EngineConfig config;
  config.contact_law = "hertz_mindlin";
  config.types = options.types;
  config.bond_materials = options.bond_materials;
  config.time_step = options.time_step;
  config.time_step_safety = options.time_step_safety;
  config.threads = options.threads;
  config.adapt_threads = options.adapt_threads;
  return config;
}

UniaxialCompressionResult run_uniaxial_compression(const Packing& bonded_model,
                                                   const UniaxialCompressionOptions& options) {
  if (options.solver == "static") return run_static_uniaxial_compression(bonded_model, options);
  const auto t0 = std::chrono::steady_clock::now();
  UniaxialCompressionResult result;
  UniaxialCompressionSpecimen specimen = prepare_uniaxial_compression(bonded_model, options, result);
  const Packing& model = specimen.model;
  const std::vector<std::uint8_t>& grip = specimen.grip;
  const double top = specimen.top;
  const bool glued = options.plate == "glued";
  const std::size_t n = model.size();

  dem::Engine engine(model, compression_engine_config(options));
  const double dt = engine.time_step();
  result.time_step = dt;
  result.plate_speed = options.strain_rate * result.height;
  // Contact plate: a wall. Glued plate: the grip particles move with it (and a wall above them
  // keeps nothing else from passing; it touches nothing).
  const std::size_t plate =
      engine.add_wall(dem::Wall{{0.0, 0.0, top}, {0.0, 0.0, -1.0}, {0.0, 0.0, -result.plate_speed}});
  std::vector<std::size_t> grip_internal;
  if (glued) {
    for (std::size_t k = 0; k < n; ++k)
      if (grip[static_cast<std::size_t>(engine.original_index()[k])]) grip_internal.push_back(k);
  }
  const auto set_plate_speed = [&](double speed) {
    engine.wall(plate).velocity = Vec3{0.0, 0.0, -speed};
    for (std::size_t k : grip_internal) engine.particles().velocity[k] = Vec3{0.0, 0.0, -speed};
  };
  set_plate_speed(result.plate_speed);
  auto plate_force = [&] {
    if (!glued) return engine.wall_force(plate).z;
    double f = 0.0;
    for (std::size_t k : grip_internal) f += engine.particles().force[k].z;
    return f;
  };

  const double total_time = options.max_strain / options.strain_rate;
  const auto total_steps = static_cast<long>(std::ceil(total_time / dt));
  const long interval = std::max(1L, total_steps / options.samples);
  // The adaptive rate: about elastic_speedup x the speed (exactly interval / fast_interval, so
  // that the points keep their strain spacing); none where the points are too close for it.
  const long fast_interval =
      std::max(1L, static_cast<long>(std::lround(static_cast<double>(interval) / options.elastic_speedup)));
  const bool adaptive = options.elastic_speedup > 1.0 && fast_interval < interval;
  const double fast_speed = result.plate_speed * static_cast<double>(interval) / static_cast<double>(fast_interval);
  if (adaptive) result.effective_speedup = static_cast<double>(interval) / static_cast<double>(fast_interval);
  // The fast plate starts smoothly: its speed rises as a half cosine over start_ramp_transits
  // times the time an elastic wave needs to cross the sample, taken at its slowest (the densest
  // particles with the softest bonds; a column's fundamental mode lasts about two transits).
  // Started at once, the fast plate would set that mode ringing with elastic_speedup times the
  // amplitude of the constant-rate run's own start (docs/opal.md, "Adaptive rate").
  constexpr double start_ramp_transits = 4.0;
  double max_slowness = 0.0;  // 1 / wave speed = sqrt(density / E) [s/m]
  for (const dem::Material& t : options.types)
    for (const dem::ElasticBond::Params& b : options.bond_materials)
      max_slowness = std::max(max_slowness, std::sqrt(t.density / b.youngs_modulus));
  const auto ramp_steps =
      adaptive ? static_cast<long>(std::ceil(start_ramp_transits * result.height * max_slowness / dt)) : 0L;
  const auto fast_phase_speed = [&](long step) {
    if (step >= ramp_steps) return fast_speed;
    return fast_speed * 0.5 *
           (1.0 - std::cos(std::numbers::pi * (static_cast<double>(step) + 0.5) / static_cast<double>(ramp_steps)));
  };
  const auto slow_sample = [&](double factor) {
    ParticleStore& particles = engine.particles();
    for (std::size_t k = 0; k < n; ++k) {
      if (particles.fixed[k]) continue;
      particles.velocity[k] *= factor;
      particles.angular_velocity[k] *= factor;
    }
  };
  const double max_displacement = options.max_strain * result.height;
  RatePhase phase;
  phase.fast = adaptive;
  PendingSnapshots pending(options);
  double peak = 0.0;
  result.stop_reason = "reached max_strain";
  const double t_start = engine.time();
  bool stopped = false;
  const auto save = [&](std::ostream& out) {
    engine.save_state(out);
    binary::write(out, static_cast<std::uint8_t>(stopped));
    binary::write_string(out, result.stop_reason);
    binary::write(out, peak);
    binary::write(out, result.strain_at_peak);
    binary::write_vector(out, result.curve);
    write_compression_snapshots(out, result.snapshots);
    if (adaptive) {
      binary::write(out, static_cast<std::uint8_t>(phase.fast));
      binary::write(out, phase.displacement);
      binary::write(out, phase.switch_step);
      binary::write(out, phase.switch_time);
      binary::write(out, result.rolled_back_steps);
    }
  };
  if (options.resume != nullptr)
    load_compression_state(*options.resume, engine, stopped, peak, result, adaptive ? &phase : nullptr);
  pending.resume(result.snapshots);
  set_plate_speed(phase.fast ? fast_phase_speed(engine.step_count()) : result.plate_speed);
  // The fast phase keeps the state after its last curve point to go back to when a bond breaks
  // (the curve, peak and snapshots of the discarded steps are not recorded yet: the break is
  // found before the point is).
  std::string rollback_state;
  double rollback_displacement = 0.0;
  while (!stopped) {
    long chunk = 0;
    if (phase.fast) {
      if (phase.displacement >= max_displacement) break;
      // The last chunk ends at max_strain (at fast_speed; shorter during the ramp, then one more).
      chunk = std::clamp(static_cast<long>(std::ceil((max_displacement - phase.displacement) / (fast_speed * dt))), 1L,
                         fast_interval);
      std::ostringstream out;
      engine.save_state(out);
      rollback_state = std::move(out).str();
      rollback_displacement = phase.displacement;
      // Step by step while the plate speeds up, then at fast_speed.
      for (long k = 0; k < chunk; ++k) {
        const long step = engine.step_count();
        if (step >= ramp_steps) {
          set_plate_speed(fast_speed);
          phase.displacement += fast_speed * dt * static_cast<double>(chunk - k);
          if (chunk - k > 1) engine.run(chunk - k - 1);
          break;
        }
        const double speed = fast_phase_speed(step);
        set_plate_speed(speed);
        phase.displacement += speed * dt;
        if (k + 1 < chunk) engine.run(1);
      }
    } else {
      // At strain_rate from the switch on (from the start without the adaptive rate: the same
      // steps as a constant-rate run).
      const long end_step =
          phase.switch_step + static_cast<long>(std::ceil((total_time - phase.displacement / result.plate_speed) / dt));
      if (engine.step_count() >= end_step) break;
      chunk = std::min(interval, end_step - engine.step_count());
      if (chunk > 1) engine.run(chunk - 1);
    }
    const dem::Diagnostics d = engine.step_measured();
    if (phase.fast && d.broken_bonds > 0) {
      // A bond broke at the fast rate: back to the last point, slowly from there.
      result.rolled_back_steps += chunk;
      std::istringstream in(rollback_state);
      engine.load_state(in);
      // The sample slows down with the plate: below its first break a column compressed at a
      // constant rate moves as the plate drives it, every velocity (and spin) in proportion to the
      // plate's speed, so scaling them by the ratio of the speeds gives the state the constant-rate
      // run has at this strain. Left at the fast run's velocities, the sample would run into the
      // slowed plate's lag (docs/opal.md, "Adaptive rate": measured both ways).
      const long saved_step = engine.step_count();
      const double speed_before = saved_step > 0 ? fast_phase_speed(saved_step - 1) : 0.0;
      if (speed_before > result.plate_speed) slow_sample(result.plate_speed / speed_before);
      phase.fast = false;
      phase.switch_step = saved_step;
      phase.switch_time = engine.time() - t_start;
      phase.displacement = rollback_displacement;
      set_plate_speed(result.plate_speed);
      continue;
    }
    UniaxialCompressionPoint p;
    p.step = d.step;
    p.time = d.time - t_start;
    // The point is the state at the start of the measured step (d.time), as at a constant rate.
    p.displacement = phase.fast ? phase.displacement - fast_phase_speed(d.step) * dt
                                : phase.displacement + result.plate_speed * (p.time - phase.switch_time);
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
    // Requested strains and stresses reached at this point, each recorded once.
    while (pending.strain_due(p.strain) || pending.stress_due(p.stress)) {
      UniaxialCompressionSnapshot s = pending.strain_due(p.strain) ? pending.take_strain() : pending.take_stress();
      s.strain = p.strain;
      s.stress = p.stress;
      s.bond_strain = engine.bond_strains();
      s.particle_stress = dem::particle_stress(engine.contact_forces(), engine.packing());
      result.snapshots.push_back(std::move(s));
    }
    if (options.stop_drop > 0.0 && peak > 0.0 && p.strain > result.strain_at_peak &&
        p.stress < options.stop_drop * peak && d.broken_bonds > 0) {
      result.stop_reason = fmt::format("stress fell below {:g} x peak after the peak", options.stop_drop);
      stopped = true;
    }
    if (options.checkpoint && !stopped) options.checkpoint(save, false);
  }
  if (options.checkpoint) options.checkpoint(save, true);
  result.steps = engine.step_count();
  result.strength = peak;
  std::vector<double> strain, stress;
  for (const auto& p : result.curve) {
    strain.push_back(p.strain);
    stress.push_back(p.stress);
  }
  result.modulus = analyze::fit_youngs_modulus(strain, stress, options.modulus_lower, options.modulus_window);
  result.youngs_modulus = result.modulus.youngs_modulus;
  for (const auto& p : result.curve)
    if (p.stress > 0.2 * peak && p.strain <= result.strain_at_peak && p.strain_energy > 0.0)
      result.max_kinetic_ratio = std::max(result.max_kinetic_ratio, p.kinetic_energy / p.strain_energy);
  result.breaks = engine.bond_breaks();
  if (adaptive && !phase.fast) result.rate_switch_strain = phase.displacement / result.height;
  for (const auto& b : result.breaks)  // every break comes after the switch to strain_rate
    result.break_strain.push_back((phase.displacement + result.plate_speed * (b.time - t_start - phase.switch_time)) /
                                  result.height);
  result.broken_bonds = result.breaks.size();
  result.model = engine.packing();  // fixed = substrate and glued plate layers
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace packlab::mechanics
