// The progress of an oscillatory shear test in a checkpoint (save_shear_progress /
// load_shear_progress): the relaxed structure, its relaxation and every finished orientation,
// exactly (binary), so that a resumed test writes the same files as an uninterrupted one.
#include <fmt/format.h>

#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/mechanics/oscillatory_shear.hpp"

namespace packlab::mechanics {

namespace {

constexpr std::uint64_t max_count = 1ULL << 32;  // a count beyond this is damage, not data

void write_count(std::ostream& out, std::size_t n) { binary::write(out, static_cast<std::uint64_t>(n)); }

std::size_t read_count(std::istream& in, const char* what) {
  std::uint64_t n = 0;
  binary::read(in, n, what);
  if (n > max_count) fail_input(fmt::format("checkpoint is damaged: implausible number of {}", what));
  return static_cast<std::size_t>(n);
}

void save_packing(std::ostream& out, const Packing& p) {
  binary::write(out, p.box);
  binary::write_vector(out, p.position);
  binary::write_vector(out, p.radius);
  binary::write_vector(out, p.type);
  binary::write_vector(out, p.velocity);
  binary::write_vector(out, p.angular_velocity);
  binary::write_vector(out, p.density);
  binary::write_vector(out, p.fixed);
  write_count(out, p.fields.size());
  for (const ScalarField& f : p.fields) {
    binary::write_string(out, f.name);
    binary::write_vector(out, f.values);
  }
  binary::write_vector(out, p.bonds.i);
  binary::write_vector(out, p.bonds.j);
  binary::write_vector(out, p.bonds.image);
  binary::write_vector(out, p.bonds.material);
  binary::write_vector(out, p.bonds.rest_length);
  binary::write_vector(out, p.bonds.state);
}

void load_packing(std::istream& in, Packing& p) {
  binary::read(in, p.box, "box");
  binary::read_vector(in, p.position, "positions");
  binary::read_vector(in, p.radius, "radii");
  binary::read_vector(in, p.type, "types");
  binary::read_vector(in, p.velocity, "velocities");
  binary::read_vector(in, p.angular_velocity, "angular velocities");
  binary::read_vector(in, p.density, "densities");
  binary::read_vector(in, p.fixed, "fixed flags");
  p.fields.resize(read_count(in, "fields"));
  for (ScalarField& f : p.fields) {
    binary::read_string(in, f.name, "field name");
    binary::read_vector(in, f.values, "field values");
  }
  binary::read_vector(in, p.bonds.i, "bonds");
  binary::read_vector(in, p.bonds.j, "bonds");
  binary::read_vector(in, p.bonds.image, "bond images");
  binary::read_vector(in, p.bonds.material, "bond materials");
  binary::read_vector(in, p.bonds.rest_length, "bond rest lengths");
  binary::read_vector(in, p.bonds.state, "bond states");
  p.validate();  // sizes and values as any packing the test accepts
}

void save_relaxation(std::ostream& out, const dem::ZeroVelocityRelaxResult& r) {
  binary::write(out, r.steps);
  binary::write(out, static_cast<std::uint8_t>(r.converged));
  binary::write(out, r.initial_unbalanced_force);
  binary::write(out, r.final_unbalanced_force);
  binary::write(out, r.last);
  binary::write_vector(out, r.history);
  binary::write_vector(out, r.unbalanced_force);
}

void load_relaxation(std::istream& in, dem::ZeroVelocityRelaxResult& r) {
  std::uint8_t converged = 0;
  binary::read(in, r.steps, "relaxation steps");
  binary::read(in, converged, "relaxation stop");
  r.converged = converged != 0;
  binary::read(in, r.initial_unbalanced_force, "relaxation forces");
  binary::read(in, r.final_unbalanced_force, "relaxation forces");
  binary::read(in, r.last, "relaxation diagnostics");
  binary::read_vector(in, r.history, "relaxation history");
  binary::read_vector(in, r.unbalanced_force, "relaxation forces");
}

// The scalar part of a ShearRun, one trivially copyable block.
struct ShearRunScalars {
  ShearOrientation orientation;
  double storage_modulus, complex_modulus, phase_angle, plate_storage_modulus;
  std::uint64_t structure_particles, plate_particles, bonds, broken_bonds;
  double max_bond_tension_ratio, max_bond_shear_ratio, max_bond_shear_force, max_bond_tension;
  double max_kinetic_to_strain, time_step;
  long steps;
  double seconds;
  std::uint64_t solver_bytes;
};

void save_run(std::ostream& out, const ShearRun& r) {
  binary::write(
      out, ShearRunScalars{r.orientation, r.storage_modulus, r.complex_modulus, r.phase_angle, r.plate_storage_modulus,
                           r.structure_particles, r.plate_particles, r.bonds, r.broken_bonds, r.max_bond_tension_ratio,
                           r.max_bond_shear_ratio, r.max_bond_shear_force, r.max_bond_tension, r.max_kinetic_to_strain,
                           r.time_step, r.steps, r.seconds, r.solver_bytes});
  binary::write_string(out, r.solver);
  write_count(out, r.samples.size());
  for (const ShearSample& s : r.samples) {
    binary::write(out, s.cycle);
    binary::write(out, s.step);
    binary::write(out, std::array<double, 7>{s.time, s.phase, s.strain, s.stress, s.plate_stress, s.kinetic_energy,
                                             s.strain_energy});
    binary::write_vector(out, s.region_stress);
  }
  binary::write_vector(out, r.cycles);
  save_relaxation(out, r.settle);
}

void load_run(std::istream& in, ShearRun& r) {
  ShearRunScalars v{};
  binary::read(in, v, "orientation results");
  r.orientation = v.orientation;
  r.storage_modulus = v.storage_modulus;
  r.complex_modulus = v.complex_modulus;
  r.phase_angle = v.phase_angle;
  r.plate_storage_modulus = v.plate_storage_modulus;
  r.structure_particles = v.structure_particles;
  r.plate_particles = v.plate_particles;
  r.bonds = v.bonds;
  r.broken_bonds = v.broken_bonds;
  r.max_bond_tension_ratio = v.max_bond_tension_ratio;
  r.max_bond_shear_ratio = v.max_bond_shear_ratio;
  r.max_bond_shear_force = v.max_bond_shear_force;
  r.max_bond_tension = v.max_bond_tension;
  r.max_kinetic_to_strain = v.max_kinetic_to_strain;
  r.time_step = v.time_step;
  r.steps = v.steps;
  r.seconds = v.seconds;
  r.solver_bytes = v.solver_bytes;
  binary::read_string(in, r.solver, "solver");
  r.samples.resize(read_count(in, "samples"));
  for (ShearSample& s : r.samples) {
    std::array<double, 7> x{};
    binary::read(in, s.cycle, "sample");
    binary::read(in, s.step, "sample");
    binary::read(in, x, "sample");
    s.time = x[0];
    s.phase = x[1];
    s.strain = x[2];
    s.stress = x[3];
    s.plate_stress = x[4];
    s.kinetic_energy = x[5];
    s.strain_energy = x[6];
    binary::read_vector(in, s.region_stress, "sample region stresses");
  }
  binary::read_vector(in, r.cycles, "cycles");
  load_relaxation(in, r.settle);
}

}  // namespace

void save_shear_progress(std::ostream& out, const OscillatoryShearResult& result) {
  binary::write(out, static_cast<std::uint8_t>(result.relaxed));
  save_relaxation(out, result.relax);
  save_packing(out, result.relaxed_packing);
  binary::write(out, result.particle_steps);
  write_count(out, result.runs.size());
  for (const ShearRun& r : result.runs) save_run(out, r);
}

void load_shear_progress(std::istream& in, OscillatoryShearResult& result) {
  std::uint8_t relaxed = 0;
  binary::read(in, relaxed, "relaxation flag");
  result.relaxed = relaxed != 0;
  load_relaxation(in, result.relax);
  load_packing(in, result.relaxed_packing);
  binary::read(in, result.particle_steps, "particle steps");
  result.runs.resize(read_count(in, "orientations"));
  for (ShearRun& r : result.runs) load_run(in, r);
}

}  // namespace packlab::mechanics
