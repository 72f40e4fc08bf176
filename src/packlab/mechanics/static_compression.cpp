// Uniaxial compression with the quasi-static solver: Young's modulus from one linear solve and
// the strength by sequential linear analysis (static_loading.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <span>

#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/mechanics/static_loading.hpp"

namespace packlab::mechanics {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// Least-squares slope of u_a against x_a over the free particles: the lateral strain.
double lateral_strain(const Packing& model, const std::vector<double>& q, int axis) {
  double sx = 0.0, su = 0.0, sxx = 0.0, sxu = 0.0, count = 0.0;
  for (std::size_t k = 0; k < model.size(); ++k) {
    if (model.fixed[k]) continue;
    const double x = model.position[k][axis], u = q[6 * k + static_cast<std::size_t>(axis)];
    sx += x;
    su += u;
    sxx += x * x;
    sxu += x * u;
    count += 1.0;
  }
  const double var = sxx - sx * sx / count;
  return var > 0.0 ? (sxu - sx * su / count) / var : nan;
}

// The solver's counts and times, carried through a checkpoint (a resumed run's solver starts at
// zero; the report gives the whole run's): the factorizations, then these counts and times.
constexpr std::array carried_counts{&StaticSolverStats::solves,    &StaticSolverStats::pcg_iterations,
                                    &StaticSolverStats::downdates, &StaticSolverStats::backward_only_solves,
                                    &StaticSolverStats::checks,    &StaticSolverStats::unchecked_solves,
                                    &StaticSolverStats::rollbacks};
constexpr std::array carried_times{&StaticSolverStats::assemble_seconds, &StaticSolverStats::factor_seconds,
                                   &StaticSolverStats::solve_seconds, &StaticSolverStats::downdate_seconds,
                                   &StaticSolverStats::check_seconds};

void write_solver_stats(std::ostream& out, const StaticSolverStats& st) {
  binary::write(out, static_cast<long>(st.factorizations));
  for (auto count : carried_counts) binary::write(out, st.*count);
  for (auto time : carried_times) binary::write(out, st.*time);
}

StaticSolverStats read_solver_stats(std::istream& in) {
  StaticSolverStats st;
  long factorizations = 0;
  binary::read(in, factorizations, "solver counts");
  bool valid = factorizations >= 0 && factorizations < (1L << 31);
  st.factorizations = static_cast<int>(factorizations);
  for (auto count : carried_counts) {
    binary::read(in, st.*count, "solver counts");
    valid = valid && st.*count >= 0;
  }
  for (auto time : carried_times) binary::read(in, st.*time, "solver times");
  if (!valid) fail_input("checkpoint is damaged: solver counts");
  return st;
}

// The counts and times of two stretches of one run (before and after a resume).
StaticSolverStats add_counts(StaticSolverStats a, const StaticSolverStats& b) {
  a.factorizations += b.factorizations;
  for (auto count : carried_counts) a.*count += b.*count;
  for (auto time : carried_times) a.*time += b.*time;
  return a;
}

}  // namespace

UniaxialCompressionResult run_static_uniaxial_compression(const Packing& bonded_model,
                                                          const UniaxialCompressionOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  UniaxialCompressionResult result;
  result.solver = "static";
  UniaxialCompressionSpecimen specimen = prepare_uniaxial_compression(bonded_model, options, result);
  Packing& model = specimen.model;
  const std::vector<std::uint8_t>& grip = specimen.grip;
  const std::size_t n = model.size();

  const StaticLinks links = linearize_links(model, compression_engine_config(options));
  StaticSolverOptions solver_options;
  solver_options.backend = options.solver_backend;
  solver_options.petsc_options = options.petsc_options;
  solver_options.threads = options.threads;
  solver_options.check_interval = options.check_interval;
  solver_options.tolerance = options.check_tolerance;
  StaticSolver solver(links, model.fixed, solver_options);

  // Unit strain: the glued particles move down by H0, the substrate stays.
  const DisplacementGradient no_gradient{};
  std::vector<double> q(6 * n, 0.0);
  for (std::size_t k = 0; k < n; ++k)
    if (grip[k]) q[6 * k + 2] = -result.height;
  std::vector<double> unit_q = q;

  const auto& params = options.bond_materials;
  auto bond_params = [&](int material) -> const dem::ElasticBond::Params& {
    return params.size() == 1 ? params[0] : params[static_cast<std::size_t>(material)];
  };
  // After each solve at unit strain, one pass over the links: the plate force (compressive
  // positive), the strain energy and every intact bond's failure ratio (its criteria,
  // eq. 16-17). The sequential linear analysis does it once per break, so the pass runs on the
  // threads, in fixed blocks summed in block order: the same sums at any thread count.
  std::vector<double> failure_ratio(links.size(), 0.0);
  constexpr std::size_t block = 4096;
  const std::size_t blocks = (links.size() + block - 1) / block;
  std::vector<double> block_force(blocks), block_energy(blocks), block_ratio(blocks);
  std::size_t intact_bonds = 0;
  for (std::size_t k = 0; k < links.size(); ++k) intact_bonds += links.bond[k] >= 0 ? 1 : 0;
  struct LinkScan {
    double plate_force = 0.0, energy = 0.0, largest_ratio = 0.0;
  };
  auto scan_links = [&](const std::vector<double>& qs) {
#pragma omp parallel for schedule(static) num_threads(std::max(1, options.threads))
    for (std::size_t b = 0; b < blocks; ++b) {
      double force = 0.0, energy = 0.0, largest = 0.0;
      for (std::size_t k = b * block; k < std::min(links.size(), (b + 1) * block); ++k) {
        failure_ratio[k] = 0.0;
        if (!solver.active(k)) continue;
        const LinkResponse r = link_response(links, k, qs, no_gradient);
        energy += r.energy;
        const auto i = static_cast<std::size_t>(links.i[k]), j = static_cast<std::size_t>(links.j[k]);
        if (grip[i] != grip[j]) force += grip[j] ? r.force_on_j.z : -r.force_on_j.z;
        if (links.bond[k] >= 0) {
          failure_ratio[k] = dem::ElasticBond::failure_ratio(
              r.load, links.geometry[k], bond_params(model.bonds.material[static_cast<std::size_t>(links.bond[k])]));
          largest = std::max(largest, failure_ratio[k]);
        }
      }
      block_force[b] = force;
      block_energy[b] = energy;
      block_ratio[b] = largest;
    }
    LinkScan scan;
    for (std::size_t b = 0; b < blocks; ++b) {
      scan.plate_force += block_force[b];
      scan.energy += block_energy[b];
      scan.largest_ratio = std::max(scan.largest_ratio, block_ratio[b]);
    }
    return scan;
  };

  PendingSnapshots pending(options);
  // The snapshot `s` (its request set) of the current network at `strain`.
  auto snapshot = [&](UniaxialCompressionSnapshot s, double strain, double stress) {
    s.strain = strain;
    s.stress = stress;
    std::vector<double> qs(unit_q.size());
    for (std::size_t k = 0; k < qs.size(); ++k) qs[k] = strain * unit_q[k];
    s.bond_strain.assign(model.bonds.size(), nan);
    for (std::size_t k = 0; k < links.size(); ++k)
      if (links.bond[k] >= 0 && solver.active(k))
        s.bond_strain[static_cast<std::size_t>(links.bond[k])] =
            link_response(links, k, qs, no_gradient).normal_displacement /
            model.bonds.rest_length[static_cast<std::size_t>(links.bond[k])];
    s.particle_stress = dem::particle_stress(link_forces(links, qs, no_gradient, solver.active_links()), model);
    result.snapshots.push_back(std::move(s));
  };

  // The strains not reached when the analysis ends, on the network last solved (unit_q).
  auto remaining_strain_snapshots = [&](double stress_per_strain) {
    while (pending.next_strain < pending.strains.size()) {
      const double e = pending.strains[pending.next_strain];
      snapshot(pending.take_strain(), e, e * stress_per_strain);
    }
  };

  auto add_point = [&](double strain, double stress_per_strain, double energy_per_strain2) {
    UniaxialCompressionPoint p;
    p.step = static_cast<long>(result.curve.size());
    p.time = nan;
    p.strain = strain;
    p.displacement = strain * result.height;
    p.stress = strain * stress_per_strain;
    p.force = p.stress * result.area;
    p.strain_energy = strain * strain * energy_per_strain2;
    p.broken_bonds = result.breaks.size();
    result.curve.push_back(p);
    if (options.on_point) options.on_point(p);
  };

  double peak = 0.0, last_stress1 = 0.0;
  result.stop_reason = "reached max_strain";
  std::vector<std::size_t> broken_links;  // per break, its link
  // Checkpoints (options.checkpoint): at the first verified solve once another
  // checkpoint_breaks bonds have broken, the state (the broken links in order and what was
  // recorded from them, the breaks that solve decided included) is a checkpoint, and the next
  // solve factorizes anew, whether or not a checkpoint is due (points taken from the clock
  // would make the results depend on the machine's speed). A resumed run switches those links
  // off in a new solver, whose first solve is that same fresh factorization.
  long next_checkpoint = options.checkpoint_breaks;
  StaticSolverStats earlier;  // of the runs before a resume
  double earlier_seconds = 0.0;
  auto seconds_so_far = [&] {
    return earlier_seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  // A bond breaks (or broke before a resume): out of the solver and the model, its place recorded.
  auto take_out = [&](std::size_t k) {
    const auto b = static_cast<std::size_t>(links.bond[k]);
    solver.deactivate(k);
    model.bonds.state[b] = 1;
    const Vec3 mid = model.position[static_cast<std::size_t>(links.i[k])] + 0.5 * links.branch[k];
    result.breaks.push_back({b, nan, model.box.wrap(mid)});
  };
  const auto save = [&](std::ostream& out) {
    binary::write_vector(out, broken_links);
    binary::write_vector(out, result.break_strain);
    binary::write_vector(out, result.curve);
    write_compression_snapshots(out, result.snapshots);
    binary::write(out, std::array<double, 4>{peak, result.strain_at_peak, result.youngs_modulus, result.poisson_ratio});
    binary::write(out, next_checkpoint);
    write_solver_stats(out, add_counts(solver.stats(), earlier));
    binary::write(out, seconds_so_far());
  };
  if (options.resume != nullptr) {
    std::istream& in = *options.resume;
    binary::read_vector(in, broken_links, "broken links");
    binary::read_vector(in, result.break_strain, "break strains");
    binary::read_vector(in, result.curve, "curve");
    read_compression_snapshots(in, result.snapshots);
    std::array<double, 4> values{};
    binary::read(in, values, "peak");
    binary::read(in, next_checkpoint, "next checkpoint");
    earlier = read_solver_stats(in);
    binary::read(in, earlier_seconds, "seconds");
    bool consistent = broken_links.size() == result.break_strain.size() && !result.curve.empty() &&
                      result.curve.back().broken_bonds == broken_links.size() &&
                      next_checkpoint > static_cast<long>(broken_links.size()) &&
                      next_checkpoint <= static_cast<long>(broken_links.size()) + options.checkpoint_breaks;
    for (double v : values) consistent = consistent && !std::isinf(v);  // nu is NaN with periodic sides
    for (double v : result.break_strain) consistent = consistent && std::isfinite(v) && v > 0.0;
    for (const UniaxialCompressionSnapshot& snap : result.snapshots)
      consistent = consistent && snap.bond_strain.size() == model.bonds.size() && snap.particle_stress.size() == n;
    if (!consistent) fail_input("checkpoint is damaged: static compression state");
    peak = values[0];
    result.strain_at_peak = values[1];
    result.youngs_modulus = values[2];
    result.poisson_ratio = values[3];
    pending.resume(result.snapshots);
    for (std::size_t k : broken_links) {
      if (k >= links.size() || links.bond[k] < 0 || !solver.active(k))
        fail_input("checkpoint is damaged: a broken link of another model");
      take_out(k);
    }
    intact_bonds -= broken_links.size();
  } else {
    add_point(0.0, 0.0, 0.0);
  }
  // With solver checks every check_interval-th re-solve (static_solver.hpp), the state after
  // the last verified solve's decisions, to go back to when a check finds the factor drifted.
  struct Verified {
    std::size_t curve = 0, breaks = 0, snapshots = 0, next_strain = 0, next_stress = 0, intact_bonds = 0;
    double peak = 0.0, strain_at_peak = 0.0;
  } verified;
  auto save_verified = [&] {
    verified = {result.curve.size(),
                result.breaks.size(),
                result.snapshots.size(),
                pending.next_strain,
                pending.next_stress,
                intact_bonds,
                peak,
                result.strain_at_peak};
  };
  auto roll_back = [&] {
    const std::span<const std::size_t> undone(broken_links.begin() + static_cast<long>(verified.breaks),
                                              broken_links.end());
    for (std::size_t k : undone) model.bonds.state[static_cast<std::size_t>(links.bond[k])] = 0;
    solver.restore(undone);
    broken_links.resize(verified.breaks);
    result.breaks.resize(verified.breaks);
    result.break_strain.resize(verified.breaks);
    result.curve.resize(verified.curve);
    result.snapshots.resize(verified.snapshots);
    pending.next_strain = verified.next_strain;
    pending.next_stress = verified.next_stress;
    intact_bonds = verified.intact_bonds;
    peak = verified.peak;
    result.strain_at_peak = verified.strain_at_peak;
  };
  save_verified();
  for (;;) {
    if (solver.verified()) {
      save_verified();
      if (static_cast<long>(broken_links.size()) >= next_checkpoint) {
        while (next_checkpoint <= static_cast<long>(broken_links.size())) next_checkpoint += options.checkpoint_breaks;
        solver.refactorize();
        if (options.checkpoint) options.checkpoint(save, false);
      }
    }
    q = unit_q;
    solver.solve(q, no_gradient);
    unit_q = q;
    if (solver.drifted()) {
      roll_back();
      continue;
    }
    const LinkScan scan = scan_links(q);
    const double stress1 = scan.plate_force / result.area;  // stress at unit strain
    last_stress1 = stress1;
    if (!result.breaks.empty() && options.stop_drop > 0.0) {
      // The load drop at the last break's strain: stop once past the peak below stop_drop x peak.
      const double strain = result.break_strain.back();
      const bool dropped = strain >= result.strain_at_peak && strain * stress1 < options.stop_drop * peak;
      // Or once no later point can come back above stop_drop x peak. A snap-back (breaks at
      // falling strains after the peak) can otherwise run for thousands of breaks below the
      // peak's strain before the test above applies. The stress at unit strain never rises: a
      // link taken out of a linear network without geometric stiffness lowers the plate's
      // stiffness (its matrix drops by a positive semi-definite term), so every later point has
      // stress <= max_strain x stress1. The peak, its strain and E are those of the longer run;
      // only the tail below stop_drop x peak is left out.
      const bool cannot_recover = options.max_strain * stress1 < options.stop_drop * peak;
      if (dropped || cannot_recover) {
        if (!solver.check_last()) {
          roll_back();
          continue;
        }
        add_point(strain, stress1, scan.energy);
        result.stop_reason =
            dropped ? fmt::format("stress fell below {:g} x peak after the peak", options.stop_drop)
                    : fmt::format("stress below {:g} x peak up to max_strain (the stress at unit strain only falls)",
                                  options.stop_drop);
        break;
      }
    }
    if (result.breaks.empty()) {
      result.youngs_modulus = stress1;
      if (options.sides == "open") {
        const double lateral = 0.5 * (lateral_strain(model, q, 0) + lateral_strain(model, q, 1));
        result.poisson_ratio = lateral / 1.0;  // axial strain -1 (compression), lateral > 0
      }
    }
    // The next bonds to fail: the largest failure ratio at unit strain; ties (within 1e-12)
    // break together.
    const double ratio = scan.largest_ratio;
    std::vector<std::size_t> critical;
    if (ratio > 0.0)
      for (std::size_t k = 0; k < links.size(); ++k)
        if (failure_ratio[k] >= ratio * (1.0 - 1e-12)) critical.push_back(k);
    const double break_strain = ratio > 0.0 ? 1.0 / ratio : std::numeric_limits<double>::infinity();
    const double energy1 = scan.energy;
    // The three ends of the run, decided here once; its last solve must be verified before it counts.
    const bool past_max_strain = break_strain > options.max_strain;
    const bool reaches_max_breaks =
        options.max_breaks > 0 && static_cast<long>(result.breaks.size() + critical.size()) >= options.max_breaks;
    const bool breaks_every_bond = intact_bonds == critical.size();
    if ((past_max_strain || reaches_max_breaks || breaks_every_bond) && !solver.check_last()) {
      roll_back();
      continue;
    }
    // Requests this branch reaches: a strain below its break strain (and max_strain), an applied
    // stress below its break load, each at the point of the branch that carries it; in the order
    // of the strain along the branch.
    const double branch_end = std::min(break_strain, options.max_strain);
    for (;;) {
      const bool strain_next =
          pending.next_strain < pending.strains.size() && pending.strains[pending.next_strain] < break_strain;
      const bool stress_next = stress1 > 0.0 && pending.next_stress < pending.stresses.size() &&
                               pending.stresses[pending.next_stress] <= branch_end * stress1;
      if (!strain_next && !stress_next) break;
      const double stress_strain = stress_next ? pending.stresses[pending.next_stress] / stress1 : 0.0;
      if (strain_next && (!stress_next || pending.strains[pending.next_strain] <= stress_strain)) {
        const double e = pending.strains[pending.next_strain];
        snapshot(pending.take_strain(), e, e * stress1);
      } else {
        snapshot(pending.take_stress(), stress_strain, stress_strain * stress1);
      }
    }
    if (past_max_strain) {
      add_point(options.max_strain, stress1, energy1);
      peak = std::max(peak, options.max_strain * stress1);
      if (peak == options.max_strain * stress1) result.strain_at_peak = options.max_strain;
      break;
    }
    add_point(break_strain, stress1, energy1);
    const double stress = break_strain * stress1;
    if (stress > peak) {
      peak = stress;
      result.strain_at_peak = break_strain;
    }
    // A run that ends with these breaks takes its strains past the end on the last network it
    // solved: its displacements belong to the links before the breaks.
    if (reaches_max_breaks || breaks_every_bond) remaining_strain_snapshots(stress1);
    for (std::size_t k : critical) {
      take_out(k);
      result.break_strain.push_back(break_strain);
      broken_links.push_back(k);
    }
    result.curve.back().broken_bonds = result.breaks.size();
    if (reaches_max_breaks) {
      result.stop_reason = fmt::format("{} bonds broke (max_breaks)", result.breaks.size());
      break;
    }
    intact_bonds -= critical.size();
    if (breaks_every_bond) {
      result.stop_reason = "every bond broke";
      break;
    }
  }
  // Strains past the end: the last network solved (a stress never reached gives no snapshot).
  remaining_strain_snapshots(last_stress1);
  result.strength = peak;
  result.broken_bonds = result.breaks.size();
  result.modulus.youngs_modulus = result.youngs_modulus;
  result.modulus.intercept = 0.0;
  result.modulus.strain_begin = 0.0;
  result.modulus.strain_end = result.curve.size() > 1 ? result.curve[1].strain : 0.0;
  const StaticSolverStats st = add_counts(solver.stats(), earlier);
  result.solves = static_cast<std::size_t>(st.solves);
  result.factorizations = static_cast<std::size_t>(st.factorizations);
  result.solver_bytes = st.matrix_bytes + st.factor_bytes;
  result.unknowns = st.unknowns;
  result.matrix_nonzeros = st.matrix_nonzeros;
  result.factor_nonzeros = st.factor_nonzeros;
  result.pcg_iterations = st.pcg_iterations;
  result.downdates = st.downdates;
  result.checks = st.checks;
  result.rollbacks = st.rollbacks;
  result.downdate_seconds = st.downdate_seconds;
  result.check_seconds = st.check_seconds;
  result.factor_seconds = st.factor_seconds + st.assemble_seconds;
  result.solve_seconds = st.solve_seconds;
  result.steps = st.solves;
  // The model as loaded at the last point: positions displaced, broken bonds marked.
  const double last = result.curve.back().strain;
  for (std::size_t k = 0; k < n; ++k)
    model.position[k] += last * Vec3{unit_q[6 * k], unit_q[6 * k + 1], unit_q[6 * k + 2]};
  result.model = std::move(model);
  result.seconds = seconds_so_far();
  return result;
}

}  // namespace packlab::mechanics
