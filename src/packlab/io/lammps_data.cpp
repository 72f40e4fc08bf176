// LAMMPS data files (atom_style sphere), read and write. Dump files: lammps_dump.cpp.
//
// Data file as written here (LAMMPS's read_data and LIGGGHTS's granular style read it):
//
//   packlab: <comment>; pbc=T T F          title line (LAMMPS ignores it)
//
//   N atoms
//   T atom types                           T = max(type) + 1
//
//   xlo xhi xlo xhi # length Lx            (and y, z)
//
//   Atoms # sphere
//
//   id type diameter density x y z         ids 1..N in packing order; type + 1; diameter = 2r
//
//   Velocities                             only when velocity or angular_velocity is present
//
//   id vx vy vz wx wy wz                   a missing one of the two is written as zeros
//
// What the data file cannot hold:
//  * Periodicity: LAMMPS sets it with the `boundary` command, not in the file. It is written as
//    'pbc=T T F' at the end of the title and read back from there; files without it (those of
//    LAMMPS itself or ../shared/peers/dem/common.sh) are taken as periodic on every axis.
//  * A packing without densities: LAMMPS requires a positive density, so 1 is written and the
//    reader always fills Packing::density from the file.
//  * The exact box length: xhi = xlo + Lx rounds, so each bounds line ends with '# length Lx'
//    (LAMMPS ignores trailing comments); the reader uses it when xlo + Lx == xhi.
//  * fixed flags, extra fields and bonds are not written.
// The reader takes LAMMPS's own write_data output too: '# sphere' style comments, image flags
// 'ix iy iz' after z (ignored: positions stay as written), atoms in any id order (sorted by id),
// other header lines and LAMMPS sections (skipped; an unknown section name is an error, as in
// LAMMPS), and zero tilt factors.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>
#include <unordered_map>

#include "packlab/core/error.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::io {

namespace detail {

void sort_by_id(std::vector<std::size_t>& order, const std::vector<long long>& ids,
                const std::filesystem::path& path) {
  order.resize(ids.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
  for (std::size_t k = 1; k < order.size(); ++k)
    if (ids[order[k]] == ids[order[k - 1]])
      fail_input(fmt::format("{}: atom id {} appears twice", path.string(), ids[order[k]]));
}

}  // namespace detail

namespace {

struct AtomRecord {
  long long id = 0;
  int type = 0;  // 0-based
  double radius = 0.0;
  double density = 0.0;
  Vec3 position;
  std::size_t line = 0;
};

struct VelocityRecord {
  long long id = 0;
  Vec3 velocity, angular_velocity;
};

// Section headers start with a letter ("Atoms", "Pair Coeffs"); data lines with a number.
bool is_data_line(std::string_view line) {
  const char c = line.front();
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
}

// The section keywords of LAMMPS data files; anything else is an error, as in LAMMPS, which
// also catches a keyword cut short by truncation.
bool is_known_section(std::string_view keyword) {
  constexpr std::string_view sections[] = {"Atoms",
                                           "Velocities",
                                           "Masses",
                                           "Ellipsoids",
                                           "Lines",
                                           "Triangles",
                                           "Bodies",
                                           "Bonds",
                                           "Angles",
                                           "Dihedrals",
                                           "Impropers",
                                           "Pair Coeffs",
                                           "PairIJ Coeffs",
                                           "Bond Coeffs",
                                           "Angle Coeffs",
                                           "Dihedral Coeffs",
                                           "Improper Coeffs",
                                           "BondBond Coeffs",
                                           "BondAngle Coeffs",
                                           "MiddleBondTorsion Coeffs",
                                           "EndBondTorsion Coeffs",
                                           "AngleTorsion Coeffs",
                                           "AngleAngleTorsion Coeffs",
                                           "BondBond13 Coeffs",
                                           "AngleAngle Coeffs",
                                           "Atom Type Labels",
                                           "Bond Type Labels",
                                           "Angle Type Labels",
                                           "Dihedral Type Labels",
                                           "Improper Type Labels"};
  return std::find(std::begin(sections), std::end(sections), keyword) != std::end(sections);
}

std::string_view strip_comment(std::string_view line) { return detail::trim(line.substr(0, line.find('#'))); }

// hi - lo is not always the length that was written (lo + L rounds), so the writer adds
// '# length L' to each bounds line; it is used when it reproduces hi, else hi - lo.
double exact_length(std::string_view line, double lo, double hi) {
  const auto hash = line.find('#');
  if (hash != std::string_view::npos) {
    const auto words = detail::split(line.substr(hash + 1));
    if (words.size() == 2 && words[0] == "length")
      if (const auto length = detail::parse_double(words[1]); length && lo + *length == hi) return *length;
  }
  return hi - lo;
}

std::array<bool, 3> parse_title_periodicity(std::string_view title, const detail::LineReader& reader) {
  const auto at = title.rfind("pbc=");
  if (at == std::string_view::npos) return {true, true, true};
  const auto flags = detail::split(title.substr(at + 4));
  std::array<bool, 3> periodic{};
  if (flags.size() < 3) reader.fail("title has 'pbc=' without three T/F flags");
  for (std::size_t a = 0; a < 3; ++a) {
    const auto flag = detail::parse_flag(flags[a]);
    if (!flag) reader.fail(fmt::format("title pbc= flag {}: expected T or F", detail::quote_token(flags[a])));
    periodic[a] = *flag;
  }
  return periodic;
}

}  // namespace

Packing read_lammps_data(const std::filesystem::path& path, const ReadOptions& options) {
  detail::LineReader reader(path);
  if (!reader.next_line()) reader.fail_end_of_file("the title line");
  Box box;
  box.periodic = parse_title_periodicity(reader.line(), reader);

  enum class Section { header, atoms, velocities, other };
  Section section = Section::header;
  std::optional<long long> atom_count;
  std::optional<int> type_count;
  std::array<bool, 3> have_bounds{};
  bool seen_atoms = false, seen_velocities = false;
  std::vector<AtomRecord> atoms;
  std::vector<VelocityRecord> velocities;

  while (reader.next_line()) {
    const std::string_view line = strip_comment(reader.line());
    if (line.empty()) continue;
    if (!is_data_line(line)) {  // a section keyword
      if (line == "Atoms") {
        if (seen_atoms) reader.fail("second Atoms section");
        const auto hash = reader.line().find('#');
        if (hash != std::string_view::npos) {
          const std::string style = detail::to_lower(detail::trim(reader.line().substr(hash + 1)));
          if (!style.empty() && style != "sphere" && style != "granular")
            reader.fail(
                fmt::format("Atoms section is for atom_style {}: only sphere (id type diameter "
                            "density x y z) is supported",
                            detail::quote_token(style)));
        }
        if (!atom_count) reader.fail("Atoms section before the 'N atoms' header line");
        section = Section::atoms;
        seen_atoms = true;
      } else if (line == "Velocities") {
        if (seen_velocities) reader.fail("second Velocities section");
        section = Section::velocities;
        seen_velocities = true;
      } else if (is_known_section(line)) {
        section = Section::other;  // Masses, Bonds, Pair Coeffs, ...: not needed here
      } else {
        reader.fail(
            fmt::format("unknown section {} (or a header line without a number)", detail::quote_token(line)));
      }
      continue;
    }
    const auto tokens = detail::split(line);
    switch (section) {
      case Section::header: {
        const std::size_t n = tokens.size();
        if (n == 2 && tokens[1] == "atoms") {
          const int count = reader.to_int(tokens[0], "the number of atoms");
          if (count < 0) reader.fail("number of atoms must be >= 0");
          atom_count = count;
        } else if (n == 3 && tokens[1] == "atom" && tokens[2] == "types") {
          type_count = reader.to_int(tokens[0], "the number of atom types");
        } else if (n == 4 && tokens[3].size() == 3 && tokens[3][1] == 'h' && tokens[3][2] == 'i' &&
                   tokens[2].size() == 3 && tokens[2][1] == 'l' && tokens[2][2] == 'o' &&
                   tokens[2][0] == tokens[3][0] && tokens[2][0] >= 'x' && tokens[2][0] <= 'z') {
          const int axis = tokens[2][0] - 'x';
          const double lo = reader.to_double(tokens[0], "the lower box bound");
          const double hi = reader.to_double(tokens[1], "the upper box bound");
          box.lo[axis] = lo;
          box.length[axis] = exact_length(reader.line(), lo, hi);
          if (!(box.length[axis] > 0.0))
            reader.fail(fmt::format("box bounds {:g} {:g}: upper must exceed lower", lo, hi));
          have_bounds[static_cast<std::size_t>(axis)] = true;
        } else if (n == 6 && tokens[3] == "xy" && tokens[4] == "xz" && tokens[5] == "yz") {
          for (int k = 0; k < 3; ++k)
            if (reader.to_double(tokens[static_cast<std::size_t>(k)], "a tilt factor") != 0.0)
              reader.fail("triclinic box (nonzero tilt factors) is not supported");
        }
        // Other header lines (bonds, bond types, extra ... per atom, ellipsoids, ...) do not matter here.
        break;
      }
      case Section::atoms: {
        if (tokens.size() != 7 && tokens.size() != 10)
          reader.fail(
              fmt::format("expected 'id type diameter density x y z [ix iy iz]' (atom_style "
                          "sphere), got {} columns",
                          tokens.size()));
        AtomRecord atom;
        atom.line = reader.line_number();
        atom.id = reader.to_int(tokens[0], "atom id");
        const int file_type = reader.to_int(tokens[1], "atom type");
        if (file_type < 1 || (type_count && file_type > *type_count))
          reader.fail(fmt::format("atom type {}: must be in 1..{} (the number of atom types)", file_type,
                                  type_count.value_or(file_type)));
        atom.type = file_type - 1;
        const double diameter = reader.to_double(tokens[2], "diameter");
        if (!(diameter > 0.0) || !std::isfinite(diameter))
          reader.fail(fmt::format("diameter {:g}: must be positive and finite", diameter));
        atom.radius = 0.5 * diameter;
        atom.density = reader.to_double(tokens[3], "density");
        if (!(atom.density > 0.0)) reader.fail(fmt::format("density {:g}: must be positive", atom.density));
        for (int a = 0; a < 3; ++a)
          atom.position[a] = reader.to_double(tokens[4 + static_cast<std::size_t>(a)], "a coordinate");
        if (tokens.size() == 10)
          for (std::size_t k = 7; k < 10; ++k) reader.to_int(tokens[k], "an image flag");
        if (atoms.size() == static_cast<std::size_t>(*atom_count))
          reader.fail(fmt::format("more than the {} atoms the header announces", *atom_count));
        atoms.push_back(atom);
        break;
      }
      case Section::velocities: {
        if (tokens.size() != 7)
          reader.fail(fmt::format("expected 'id vx vy vz wx wy wz', got {} columns", tokens.size()));
        VelocityRecord record;
        record.id = reader.to_int(tokens[0], "atom id");
        for (int a = 0; a < 3; ++a) {
          record.velocity[a] =
              reader.to_double(tokens[1 + static_cast<std::size_t>(a)], "a velocity component");
          record.angular_velocity[a] =
              reader.to_double(tokens[4 + static_cast<std::size_t>(a)], "an angular velocity component");
        }
        velocities.push_back(record);
        break;
      }
      case Section::other: break;
    }
  }

  if (!atom_count) reader.fail_end_of_file("an 'N atoms' header line");
  for (std::size_t a = 0; a < 3; ++a)
    if (!have_bounds[a])
      fail_input(fmt::format("{}: no '{}lo {}hi' header line", path.string(), "xyz"[a], "xyz"[a]));
  if (atoms.size() != static_cast<std::size_t>(*atom_count))
    reader.fail_end_of_file(
        fmt::format("{} lines in the Atoms section, found {}", *atom_count, atoms.size()));
  if (seen_velocities && velocities.size() != atoms.size())
    reader.fail_end_of_file(
        fmt::format("{} lines in the Velocities section, found {}", atoms.size(), velocities.size()));

  std::vector<long long> ids(atoms.size());
  std::transform(atoms.begin(), atoms.end(), ids.begin(), [](const AtomRecord& a) { return a.id; });
  std::vector<std::size_t> order;
  detail::sort_by_id(order, ids, path);
  Packing packing;
  std::unordered_map<long long, std::size_t> index_of_id;
  std::vector<std::size_t> lines;
  for (const std::size_t k : order) {
    lines.push_back(atoms[k].line);
    index_of_id.emplace(atoms[k].id, packing.size());
    packing.add(atoms[k].position, atoms[k].radius, atoms[k].type);
    packing.density.push_back(atoms[k].density);
  }
  if (seen_velocities) {
    packing.velocity.resize(packing.size());
    packing.angular_velocity.resize(packing.size());
    std::vector<bool> seen(packing.size(), false);
    for (const auto& record : velocities) {
      const auto found = index_of_id.find(record.id);
      if (found == index_of_id.end())
        fail_input(fmt::format("{}: Velocities section names atom id {}, which is not in Atoms",
                               path.string(), record.id));
      if (seen[found->second])
        fail_input(fmt::format("{}: Velocities section lists atom id {} twice", path.string(), record.id));
      seen[found->second] = true;
      packing.velocity[found->second] = record.velocity;
      packing.angular_velocity[found->second] = record.angular_velocity;
    }
  }
  detail::finish_reading(packing, box, options, path, lines);
  return packing;
}

void write_lammps_data(const Packing& packing, const std::filesystem::path& path,
                       const WriteOptions& options) {
  detail::validate_for_writing(packing, path);
  const Box box = detail::box_for_writing(packing);
  const int type_count =
      packing.size() == 0 ? 1 : *std::max_element(packing.type.begin(), packing.type.end()) + 1;
  const bool with_velocities = !packing.velocity.empty() || !packing.angular_velocity.empty();
  write_atomically(path, [&](std::ostream& out) {
    fmt::memory_buffer buffer;
    auto flush = [&] {
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      buffer.clear();
    };
    auto it = std::back_inserter(buffer);
    // pbc= goes last: the reader takes the last one, so a comment cannot fake it.
    const std::string comment = options.comment.empty() ? "" : detail::single_line(options.comment) + ";";
    fmt::format_to(it, "packlab: {} pbc={} {} {}\n\n", comment, box.periodic[0] ? 'T' : 'F',
                   box.periodic[1] ? 'T' : 'F', box.periodic[2] ? 'T' : 'F');
    fmt::format_to(it, "{} atoms\n{} atom types\n\n", packing.size(), type_count);
    for (int a = 0; a < 3; ++a)
      fmt::format_to(it, "{:.17g} {:.17g} {}lo {}hi # length {:.17g}\n", box.lo[a], box.lo[a] + box.length[a],
                     "xyz"[a], "xyz"[a], box.length[a]);
    fmt::format_to(it, "\nAtoms # sphere\n\n");
    for (std::size_t k = 0; k < packing.size(); ++k) {
      const Vec3& p = packing.position[k];
      const double density = packing.density.empty() ? 1.0 : packing.density[k];
      fmt::format_to(it, "{} {} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n", k + 1, packing.type[k] + 1,
                     2.0 * packing.radius[k], density, p.x, p.y, p.z);
      if (buffer.size() > (1u << 20)) flush();
    }
    if (with_velocities) {
      fmt::format_to(it, "\nVelocities\n\n");
      for (std::size_t k = 0; k < packing.size(); ++k) {
        const Vec3 v = packing.velocity.empty() ? Vec3{} : packing.velocity[k];
        const Vec3 w = packing.angular_velocity.empty() ? Vec3{} : packing.angular_velocity[k];
        fmt::format_to(it, "{} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n", k + 1, v.x, v.y, v.z, w.x,
                       w.y, w.z);
        if (buffer.size() > (1u << 20)) flush();
      }
    }
    flush();
  });
}

}  // namespace packlab::io
