// LAMMPS files: data files (atom_style sphere, read and write) and dump files (read only).
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
//
// Dump (first frame only): ITEM: TIMESTEP / NUMBER OF ATOMS / BOX BOUNDS [xy xz yz] f1 f2 f3 /
// ATOMS col... with columns in any order. An axis is periodic when its flag is 'pp'. Positions
// come from the first present of x, xu, xs, xsu (scaled: lo + s L); size from radius (else
// diameter); type (1-based, optional), vx vy vz, omegax omegay omegaz, density (optional); id
// sorts the atoms; every other numeric column, and an incomplete vx/vy/vz or omega triple,
// becomes an extra field under its own name (c_coord, fx, mass, ...).
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

namespace {

struct AtomRecord {
  long long id = 0;
  int type = 0;  // 0-based
  double radius = 0.0;
  double density = 0.0;
  Vec3 position;
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

// Sorts atoms by id (LAMMPS writes them in processor order) and rejects repeated ids.
void sort_by_id(std::vector<std::size_t>& order, const std::vector<long long>& ids,
                const std::filesystem::path& path) {
  order.resize(ids.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
  for (std::size_t k = 1; k < order.size(); ++k)
    if (ids[order[k]] == ids[order[k - 1]])
      fail_input(fmt::format("{}: atom id {} appears twice", path.string(), ids[order[k]]));
}

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
  sort_by_id(order, ids, path);
  Packing packing;
  std::unordered_map<long long, std::size_t> index_of_id;
  for (const std::size_t k : order) {
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
  detail::finish_reading(packing, box, options, path);
  return packing;
}

void write_lammps_data(const Packing& packing, const std::filesystem::path& path,
                       const WriteOptions& options) {
  detail::validate_for_writing(packing, path);
  const Box& box = packing.box;
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

namespace {

enum class DumpColumn {
  id, type, x, y, z, xu, yu, zu, xs, ys, zs, xsu, ysu, zsu, radius, diameter,
  vx, vy, vz, omegax, omegay, omegaz, density, skipped, field
};

struct NamedDumpColumn {
  std::string_view name;
  DumpColumn column;
};

constexpr NamedDumpColumn dump_columns[] = {
    {"id", DumpColumn::id},
    {"type", DumpColumn::type},
    {"x", DumpColumn::x},
    {"y", DumpColumn::y},
    {"z", DumpColumn::z},
    {"xu", DumpColumn::xu},
    {"yu", DumpColumn::yu},
    {"zu", DumpColumn::zu},
    {"xs", DumpColumn::xs},
    {"ys", DumpColumn::ys},
    {"zs", DumpColumn::zs},
    {"xsu", DumpColumn::xsu},
    {"ysu", DumpColumn::ysu},
    {"zsu", DumpColumn::zsu},
    {"radius", DumpColumn::radius},
    {"diameter", DumpColumn::diameter},
    {"vx", DumpColumn::vx},
    {"vy", DumpColumn::vy},
    {"vz", DumpColumn::vz},
    {"omegax", DumpColumn::omegax},
    {"omegay", DumpColumn::omegay},
    {"omegaz", DumpColumn::omegaz},
    {"density", DumpColumn::density},
    {"element", DumpColumn::skipped},
};

// Which column gives coordinate `axis`, and whether it is scaled; fails unless exactly one does.
struct AxisSource {
  std::size_t column = 0;
  bool scaled = false;
};

}  // namespace

Packing read_lammps_dump(const std::filesystem::path& path, const ReadOptions& options) {
  detail::LineReader reader(path);
  std::optional<long long> atom_count;
  std::optional<Box> box;
  auto next_data_line = [&](std::string_view expected) {
    if (!reader.next_line()) reader.fail_end_of_file(expected);
    return detail::trim(reader.line());
  };

  // Items before ATOMS, in any order; ATOMS ends the first frame.
  std::string_view item;
  if (!reader.next_line()) reader.fail_end_of_file("'ITEM: TIMESTEP'");
  while (true) {
    const std::string_view line = detail::trim(reader.line());
    if (!line.starts_with("ITEM:")) {
      reader.fail(fmt::format("expected an 'ITEM: ...' line, got {}", detail::quote_token(line)));
    }
    item = detail::trim(line.substr(5));
    if (item.starts_with("ATOMS")) break;
    if (item == "NUMBER OF ATOMS") {
      const std::string_view count_line = next_data_line("the number of atoms");
      const auto count = detail::parse_integer(count_line);
      if (!count || *count < 0)
        reader.fail(fmt::format("expected the number of atoms, got {}", detail::quote_token(count_line)));
      atom_count = *count;
      if (!reader.next_line()) reader.fail_end_of_file("'ITEM: BOX BOUNDS'");
    } else if (item.starts_with("BOX BOUNDS")) {
      const auto words = detail::split(item.substr(10));
      const bool triclinic = words.size() >= 3 && words[0] == "xy" && words[1] == "xz" && words[2] == "yz";
      if (!words.empty() && words[0] == "abc")
        reader.fail("general triclinic box (BOX BOUNDS abc origin) is not supported");
      const std::size_t first_flag = triclinic ? 3 : 0;
      Box parsed;
      if (words.size() == first_flag + 3) {
        for (std::size_t a = 0; a < 3; ++a) parsed.periodic[a] = words[first_flag + a] == "pp";
      } else if (words.size() != first_flag) {
        reader.fail("expected 'ITEM: BOX BOUNDS' followed by three boundary flags such as 'pp pp ff'");
      }
      for (int a = 0; a < 3; ++a) {
        const auto bounds = detail::split(next_data_line("three lines of box bounds"));
        if (bounds.size() != (triclinic ? 3u : 2u))
          reader.fail(fmt::format("expected {} numbers (box bounds{}), got {}", triclinic ? 3 : 2,
                                  triclinic ? " and a tilt factor" : "", bounds.size()));
        const double lo = reader.to_double(bounds[0], "the lower box bound");
        const double hi = reader.to_double(bounds[1], "the upper box bound");
        if (triclinic && reader.to_double(bounds[2], "a tilt factor") != 0.0)
          reader.fail("triclinic box (nonzero tilt factor) is not supported");
        if (!(hi > lo)) reader.fail(fmt::format("box bounds {:g} {:g}: upper must exceed lower", lo, hi));
        parsed.lo[a] = lo;
        parsed.length[a] = hi - lo;
      }
      box = parsed;
      if (!reader.next_line()) reader.fail_end_of_file("'ITEM: ATOMS ...'");
    } else {
      // TIMESTEP, TIME, UNITS or anything else: skip its lines up to the next ITEM.
      do {
        if (!reader.next_line()) reader.fail_end_of_file("'ITEM: ATOMS ...'");
      } while (!detail::trim(reader.line()).starts_with("ITEM:"));
    }
  }
  if (!atom_count) reader.fail("ITEM: ATOMS before ITEM: NUMBER OF ATOMS");
  if (!box) reader.fail("ITEM: ATOMS before ITEM: BOX BOUNDS");

  // Column layout.
  // Copied: `item` views the reader's line buffer, which the atom lines overwrite.
  std::vector<std::string> names;
  for (const auto name : detail::split(item.substr(5))) names.emplace_back(name);
  if (names.empty()) reader.fail("ITEM: ATOMS names no columns");
  Packing packing;
  std::vector<DumpColumn> columns;
  for (std::size_t c = 0; c < names.size(); ++c) {
    const auto known = std::find_if(std::begin(dump_columns), std::end(dump_columns),
                                    [&](const NamedDumpColumn& d) { return d.name == names[c]; });
    for (std::size_t earlier = 0; earlier < c; ++earlier)
      if (names[earlier] == names[c])
        reader.fail(fmt::format("column {} appears twice", detail::quote_token(names[c])));
    columns.push_back(known != std::end(dump_columns) ? known->column : DumpColumn::field);
  }
  auto find = [&](DumpColumn wanted) -> std::optional<std::size_t> {
    const auto at = std::find(columns.begin(), columns.end(), wanted);
    if (at == columns.end()) return std::nullopt;
    return static_cast<std::size_t>(at - columns.begin());
  };
  // An incomplete velocity or angular velocity triple is kept as extra fields.
  for (const auto& triple : {std::array{DumpColumn::vx, DumpColumn::vy, DumpColumn::vz},
                             std::array{DumpColumn::omegax, DumpColumn::omegay, DumpColumn::omegaz}}) {
    if (find(triple[0]) && find(triple[1]) && find(triple[2])) continue;
    for (auto& column : columns)
      if (std::find(triple.begin(), triple.end(), column) != triple.end()) column = DumpColumn::field;
  }
  std::vector<std::size_t> field_of_column(names.size(), 0);
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (columns[c] != DumpColumn::field) continue;
    field_of_column[c] = packing.fields.size();
    packing.fields.push_back({names[c], {}});
  }
  // Coordinates: the first present of x (wrapped), xu (unwrapped), xs, xsu (scaled).
  std::array<AxisSource, 3> axis_source;
  constexpr DumpColumn plain[] = {DumpColumn::x, DumpColumn::y, DumpColumn::z};
  constexpr DumpColumn unwrapped[] = {DumpColumn::xu, DumpColumn::yu, DumpColumn::zu};
  constexpr DumpColumn scaled[] = {DumpColumn::xs, DumpColumn::ys, DumpColumn::zs};
  constexpr DumpColumn scaled_unwrapped[] = {DumpColumn::xsu, DumpColumn::ysu, DumpColumn::zsu};
  for (std::size_t a = 0; a < 3; ++a) {
    bool found = false;
    for (const auto& [kind, is_scaled] : {std::pair{plain[a], false}, std::pair{unwrapped[a], false},
                                          std::pair{scaled[a], true}, std::pair{scaled_unwrapped[a], true}}) {
      if (const auto c = find(kind); c && !found) {
        axis_source[a] = {*c, is_scaled};
        found = true;
      }
    }
    if (!found) reader.fail(fmt::format("ITEM: ATOMS has none of the columns {0} {0}u {0}s {0}su", "xyz"[a]));
  }
  const auto radius_column = find(DumpColumn::radius);
  const auto diameter_column = find(DumpColumn::diameter);
  if (!radius_column && !diameter_column)
    reader.fail("ITEM: ATOMS has neither a radius nor a diameter column");
  const auto id_column = find(DumpColumn::id);
  const auto type_column = find(DumpColumn::type);
  const auto density_column = find(DumpColumn::density);
  const std::array<std::optional<std::size_t>, 3> velocity_columns{find(DumpColumn::vx), find(DumpColumn::vy),
                                                                   find(DumpColumn::vz)};
  const std::array<std::optional<std::size_t>, 3> omega_columns{
      find(DumpColumn::omegax), find(DumpColumn::omegay), find(DumpColumn::omegaz)};
  const bool with_velocity = velocity_columns[0].has_value();
  const bool with_omega = omega_columns[0].has_value();

  // Atom lines.
  std::vector<long long> ids;
  for (long long n = 0; n < *atom_count; ++n) {
    if (!reader.next_line())
      reader.fail_end_of_file(fmt::format("{} atom lines after ITEM: ATOMS, found {}", *atom_count, n));
    const auto tokens = detail::split(reader.line());
    if (tokens.size() != columns.size())
      reader.fail(
          fmt::format("expected {} columns as ITEM: ATOMS says, got {}", columns.size(), tokens.size()));
    Vec3 position;
    for (std::size_t a = 0; a < 3; ++a) {
      const double value = reader.to_double(tokens[axis_source[a].column], "a coordinate");
      const int axis = static_cast<int>(a);
      position[axis] = axis_source[a].scaled ? box->lo[axis] + value * box->length[axis] : value;
    }
    const double radius = radius_column ? reader.to_double(tokens[*radius_column], "radius")
                                        : 0.5 * reader.to_double(tokens[*diameter_column], "diameter");
    if (!(radius > 0.0) || !std::isfinite(radius))
      reader.fail(fmt::format("radius {:g}: must be positive and finite", radius));
    int type = 0;
    if (type_column) {
      const int file_type = reader.to_int(tokens[*type_column], "atom type");
      if (file_type < 1) reader.fail(fmt::format("atom type {}: must be >= 1", file_type));
      type = file_type - 1;
    }
    if (id_column) ids.push_back(static_cast<long long>(reader.to_int(tokens[*id_column], "atom id")));
    if (density_column) packing.density.push_back(reader.to_double(tokens[*density_column], "density"));
    if (with_velocity) {
      Vec3 v;
      for (std::size_t a = 0; a < 3; ++a)
        v[static_cast<int>(a)] = reader.to_double(tokens[*velocity_columns[a]], "a velocity component");
      packing.velocity.push_back(v);
    }
    if (with_omega) {
      Vec3 w;
      for (std::size_t a = 0; a < 3; ++a)
        w[static_cast<int>(a)] = reader.to_double(tokens[*omega_columns[a]], "an angular velocity component");
      packing.angular_velocity.push_back(w);
    }
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c] == DumpColumn::field)
        packing.fields[field_of_column[c]].values.push_back(reader.to_double(tokens[c], names[c]));
    packing.add(position, radius, type);
  }

  if (id_column) {
    std::vector<std::size_t> order;
    sort_by_id(order, ids, path);
    auto permute = [&](auto& values) {
      if (values.empty()) return;
      auto copy = values;
      for (std::size_t k = 0; k < order.size(); ++k) values[k] = copy[order[k]];
    };
    permute(packing.position);
    permute(packing.radius);
    permute(packing.type);
    permute(packing.velocity);
    permute(packing.angular_velocity);
    permute(packing.density);
    for (auto& field : packing.fields) permute(field.values);
  }
  detail::finish_reading(packing, box, options, path);
  return packing;
}

}  // namespace packlab::io
