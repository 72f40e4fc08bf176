// LAMMPS dump files (read only). Data files: lammps_data.cpp.
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

#include "packlab/core/error.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::io {

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
  std::vector<std::size_t> lines;
  for (long long n = 0; n < *atom_count; ++n) {
    if (!reader.next_line())
      reader.fail_end_of_file(fmt::format("{} atom lines after ITEM: ATOMS, found {}", *atom_count, n));
    if (detail::trim(reader.line()).starts_with("ITEM:"))
      reader.fail(fmt::format("NUMBER OF ATOMS is {}, but the frame has only {} atom lines: the count must "
                              "equal the number of atom lines",
                              *atom_count, n));
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
        packing.fields[field_of_column[c]].values.push_back(reader.to_value(tokens[c], names[c]));
    packing.add(position, radius, type);
    lines.push_back(reader.line_number());
  }
  // Only the first frame is read; what follows it is the next frame's ITEM: line or nothing.
  while (reader.next_line()) {
    const std::string_view line = detail::trim(reader.line());
    if (line.empty()) continue;
    if (line.starts_with("ITEM:")) break;
    reader.fail(fmt::format("NUMBER OF ATOMS is {}, but more atom lines follow: the count must equal the "
                            "number of atom lines",
                            *atom_count));
  }

  if (id_column) {
    std::vector<std::size_t> order;
    detail::sort_by_id(order, ids, path);
    auto permute = [&](auto& values) {
      if (values.empty()) return;
      auto copy = values;
      for (std::size_t k = 0; k < order.size(); ++k) values[k] = copy[order[k]];
    };
    permute(lines);
    permute(packing.position);
    permute(packing.radius);
    permute(packing.type);
    permute(packing.velocity);
    permute(packing.angular_velocity);
    permute(packing.density);
    for (auto& field : packing.fields) permute(field.values);
  }
  detail::finish_reading(packing, box, options, path, lines);
  return packing;
}

}  // namespace packlab::io
