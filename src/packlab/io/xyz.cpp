// Extended XYZ (libAtoms/QUIP convention, read by OVITO and ASE):
//
//   N
//   Lattice="Lx 0 0 0 Ly 0 0 0 Lz" Origin="x y z" pbc="T T F" Properties=species:S:1:pos:R:3:...
//       ...:radius:R:1[...] Comment="..."                          (all on line 2)
//   T0 x y z r ...                                                 (one line per particle)
//
// Written columns: species, pos, radius, then when present velo:R:3, omega:R:3, density:R:1,
// fixed:I:1 and every extra field as <name>:R:1. These names are the ones OVITO maps to its
// standard properties (Particle Type, Position, Radius, Velocity, Angular Velocity).
//
// Type: the species string is "T<type>" (T0, T1, ...). There is no separate type:I:1 column
// because OVITO maps both 'species' and 'type' to its one Particle Type property. On reading, a
// type:I:1 column wins; otherwise species "T<n>" or "<n>" give type n, and other names (element
// symbols) are numbered 0, 1, ... in alphabetical order, as OVITO orders named types.
//
// The reader takes the properties in any order and case, also under OVITO's and ASE's names
// (position, velocity, Radius, diameter, id (ignored), ...); other R/I/L scalars become extra
// fields; anything else is an error. Lattice must be diagonal (the box is a cuboid); Origin
// (or cell_origin) defaults to 0 and pbc to "T T T" when Lattice is present. Without Lattice the
// box is the bounding box (or ReadOptions.box). Only the first frame of a trajectory is read.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>

#include "packlab/core/error.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::io {

namespace {

enum class Target {
  position, radius, diameter, species, type, velocity, angular_velocity, density, fixed, ignored, field
};

struct Property {
  std::string name;
  char kind = 'R';  // S string, R real, I integer, L logical
  int count = 1;
  Target target = Target::field;
  std::size_t field_index = 0;  // into Packing::fields when target == field
};

struct KnownProperty {
  std::string_view name;  // lower case
  Target target;
  int count;
  std::string_view kinds;  // accepted kinds
};

// Names as written by packlab, OVITO, ASE and QUIP.
constexpr KnownProperty known_properties[] = {
    {"pos", Target::position, 3, "R"},
    {"position", Target::position, 3, "R"},
    {"positions", Target::position, 3, "R"},
    {"radius", Target::radius, 1, "RI"},
    {"radii", Target::radius, 1, "RI"},
    {"diameter", Target::diameter, 1, "RI"},
    {"species", Target::species, 1, "S"},
    {"element", Target::species, 1, "S"},
    {"atom_types", Target::species, 1, "S"},
    {"type", Target::type, 1, "IS"},
    {"velo", Target::velocity, 3, "R"},
    {"vel", Target::velocity, 3, "R"},
    {"velocity", Target::velocity, 3, "R"},
    {"velocities", Target::velocity, 3, "R"},
    {"omega", Target::angular_velocity, 3, "R"},
    {"angular_velocity", Target::angular_velocity, 3, "R"},
    {"density", Target::density, 1, "RI"},
    {"fixed", Target::fixed, 1, "IL"},
    {"id", Target::ignored, 1, "I"},
};

struct KeyValue {
  std::string key;  // lower case
  std::string_view value;
};

// key=value, key="quoted value" and bare flag words, separated by blanks.
std::vector<KeyValue> parse_comment_line(std::string_view line, const detail::LineReader& reader) {
  std::vector<KeyValue> pairs;
  std::size_t pos = 0;
  auto is_blank = [](char c) { return c == ' ' || c == '\t'; };
  while (pos < line.size()) {
    while (pos < line.size() && is_blank(line[pos])) ++pos;
    if (pos >= line.size()) break;
    const std::size_t key_begin = pos;
    while (pos < line.size() && !is_blank(line[pos]) && line[pos] != '=') ++pos;
    KeyValue pair{detail::to_lower(line.substr(key_begin, pos - key_begin)), {}};
    if (pos < line.size() && line[pos] == '=') {
      ++pos;
      if (pos < line.size() && line[pos] == '"') {
        const auto close = line.find('"', pos + 1);
        if (close == std::string_view::npos)
          reader.fail(fmt::format("value of {} has no closing '\"'", detail::quote_token(pair.key)));
        pair.value = line.substr(pos + 1, close - pos - 1);
        pos = close + 1;
      } else {
        const std::size_t value_begin = pos;
        while (pos < line.size() && !is_blank(line[pos])) ++pos;
        pair.value = line.substr(value_begin, pos - value_begin);
      }
    }
    pairs.push_back(pair);
  }
  return pairs;
}

std::vector<Property> parse_properties(std::string_view spec, Packing& packing,
                                       const detail::LineReader& reader) {
  const auto parts = detail::split(spec, ":");
  if (parts.empty() || parts.size() % 3 != 0)
    reader.fail(
        fmt::format("Properties={} is not a list of name:type:count triples", detail::quote_token(spec)));
  std::vector<Property> properties;
  for (std::size_t k = 0; k < parts.size(); k += 3) {
    Property property;
    property.name = std::string(parts[k]);
    const std::string kind = detail::to_lower(parts[k + 1]);
    if (kind != "s" && kind != "r" && kind != "i" && kind != "l")
      reader.fail(fmt::format("property {} has type {}: expected S, R, I or L", detail::quote_token(parts[k]),
                              detail::quote_token(parts[k + 1])));
    property.kind = static_cast<char>(kind[0] - 'a' + 'A');
    const auto count = detail::parse_integer(parts[k + 2]);
    if (!count || *count < 1 || *count > 1000)
      reader.fail(fmt::format("property {} has column count {}: expected a positive integer",
                              detail::quote_token(parts[k]), detail::quote_token(parts[k + 2])));
    property.count = static_cast<int>(*count);

    const std::string lower = detail::to_lower(property.name);
    const auto known = std::find_if(std::begin(known_properties), std::end(known_properties),
                                    [&](const KnownProperty& p) { return p.name == lower; });
    if (known != std::end(known_properties)) {
      if (known->count != property.count || known->kinds.find(property.kind) == std::string_view::npos)
        reader.fail(fmt::format("property {}:{}:{} should have {} column(s) of type {}", property.name,
                                property.kind, property.count, known->count, known->kinds.substr(0, 1)));
      // A string 'type' column holds names, like species.
      property.target =
          known->target == Target::type && property.kind == 'S' ? Target::species : known->target;
    } else if (property.kind != 'S' && property.count == 1) {
      if (packing.field(property.name))
        reader.fail(fmt::format("property {} appears twice", detail::quote_token(property.name)));
      property.target = Target::field;
      property.field_index = packing.fields.size();
      packing.fields.push_back({property.name, {}});
    } else {
      reader.fail(
          fmt::format("unknown property {}:{}:{}: only scalar (R, I or L with 1 column) "
                      "extra properties are supported",
                      property.name, property.kind, property.count));
    }
    for (const auto& earlier : properties)
      if (earlier.target == property.target && property.target != Target::field &&
          property.target != Target::ignored)
        reader.fail(
            fmt::format("properties {} and {} both give the same quantity", earlier.name, property.name));
    properties.push_back(std::move(property));
  }
  auto has = [&](Target t) {
    return std::any_of(properties.begin(), properties.end(),
                       [t](const Property& p) { return p.target == t; });
  };
  if (!has(Target::position)) reader.fail("Properties has no pos:R:3");
  if (!has(Target::radius) && !has(Target::diameter)) reader.fail("Properties has no radius:R:1");
  if (has(Target::radius) && has(Target::diameter)) reader.fail("Properties has both radius and diameter");
  return properties;
}

Box parse_lattice(const std::vector<KeyValue>& pairs, std::string_view lattice,
                  const detail::LineReader& reader) {
  const auto numbers = detail::split(lattice);
  if (numbers.size() != 9) reader.fail(fmt::format("Lattice has {} numbers: expected 9", numbers.size()));
  Box box;
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) {
      const double value =
          reader.to_double(numbers[static_cast<std::size_t>(3 * row + col)], "a Lattice entry");
      if (row == col) {
        if (!(value > 0.0) || !std::isfinite(value))
          reader.fail(fmt::format("Lattice vector {} has length {:g}: must be positive", row + 1, value));
        box.length[row] = value;
      } else if (value != 0.0) {
        reader.fail(
            "Lattice is not diagonal: only cuboid boxes (Lattice=\"Lx 0 0 0 Ly 0 0 0 Lz\") are supported");
      }
    }
  for (const auto& pair : pairs) {
    if (pair.key == "origin" || pair.key == "cell_origin") {
      const auto origin = detail::split(pair.value);
      if (origin.size() != 3) reader.fail(fmt::format("Origin has {} numbers: expected 3", origin.size()));
      for (int a = 0; a < 3; ++a)
        box.lo[a] = reader.to_double(origin[static_cast<std::size_t>(a)], "an Origin entry");
    } else if (pair.key == "pbc") {
      const auto flags = detail::split(pair.value);
      if (flags.size() != 3)
        reader.fail(fmt::format("pbc has {} entries: expected 3 (e.g. pbc=\"T T F\")", flags.size()));
      for (int a = 0; a < 3; ++a) {
        const auto flag = detail::parse_flag(flags[static_cast<std::size_t>(a)]);
        if (!flag)
          reader.fail(fmt::format("pbc entry {}: expected T or F",
                                  detail::quote_token(flags[static_cast<std::size_t>(a)])));
        box.periodic[a] = *flag;
      }
    }
  }
  return box;
}

// "T<n>" or "<n>" -> n, for species written by packlab or as plain numbers.
std::optional<int> numeric_species(std::string_view species) {
  if (!species.empty() && species.front() == 'T') species.remove_prefix(1);
  const auto value = detail::parse_integer(species);
  if (!value || *value < 0 || *value > std::numeric_limits<int>::max()) return std::nullopt;
  return static_cast<int>(*value);
}

std::vector<int> types_from_species(const std::vector<std::string>& species) {
  std::vector<int> types(species.size());
  bool all_numeric = true;
  for (std::size_t k = 0; k < species.size() && all_numeric; ++k) {
    const auto value = numeric_species(species[k]);
    if (value)
      types[k] = *value;
    else
      all_numeric = false;
  }
  if (all_numeric) return types;
  std::map<std::string, int> index;  // sorted by name
  for (const auto& name : species) index.emplace(name, 0);
  int next = 0;
  for (auto& entry : index) entry.second = next++;
  for (std::size_t k = 0; k < species.size(); ++k) types[k] = index[species[k]];
  return types;
}

}  // namespace

Packing read_xyz(const std::filesystem::path& path, const ReadOptions& options) {
  detail::LineReader reader(path);
  if (!reader.next_line()) reader.fail_end_of_file("the number of particles on line 1");
  const auto count = detail::parse_integer(detail::trim(reader.line()));
  if (!count || *count < 0)
    reader.fail(fmt::format("expected the number of particles, got {}",
                            detail::quote_token(detail::trim(reader.line()))));
  if (!reader.next_line()) reader.fail_end_of_file("the comment line (Lattice=... Properties=...)");

  Packing packing;
  const std::string comment_line(reader.line());
  const auto pairs = parse_comment_line(comment_line, reader);
  std::optional<Box> file_box;
  std::vector<Property> properties;
  for (const auto& pair : pairs) {
    if (pair.key == "lattice") file_box = parse_lattice(pairs, pair.value, reader);
    if (pair.key == "properties") properties = parse_properties(pair.value, packing, reader);
  }
  if (properties.empty())
    reader.fail("no Properties=... key: expected e.g. Properties=species:S:1:pos:R:3:radius:R:1");
  std::size_t column_count = 0;
  bool has_type_column = false;
  bool has_species_column = false;
  for (const auto& property : properties) {
    column_count += static_cast<std::size_t>(property.count);
    has_type_column |= property.target == Target::type;
    has_species_column |= property.target == Target::species;
  }
  const bool has_velocity = std::any_of(properties.begin(), properties.end(),
                                        [](const Property& p) { return p.target == Target::velocity; });
  const bool has_angular_velocity = std::any_of(properties.begin(), properties.end(), [](const Property& p) {
    return p.target == Target::angular_velocity;
  });
  std::vector<std::string> species;
  const bool species_gives_type = has_species_column && !has_type_column;

  std::vector<std::size_t> lines;
  for (long long n = 0; n < *count; ++n) {
    if (!reader.next_line())
      reader.fail_end_of_file(fmt::format("{} particle lines after line 2, found {}", *count, n));
    const auto tokens = detail::split(reader.line(), " \t");
    if (tokens.size() == 1 && detail::parse_integer(tokens[0]))
      reader.fail(fmt::format("line 1 announces {} particles, but only {} particle lines follow before this "
                              "line (the count of the next frame?): the count must equal the number of "
                              "particle lines",
                              *count, n));
    if (tokens.size() != column_count)
      reader.fail(fmt::format("expected {} columns as Properties says, got {}", column_count, tokens.size()));
    Vec3 position, velocity, angular_velocity;
    double radius = 0.0;
    int type = 0;
    std::size_t column = 0;
    for (const auto& property : properties) {
      const auto token = [&](int component) { return tokens[column + static_cast<std::size_t>(component)]; };
      switch (property.target) {
        case Target::position:
          for (int a = 0; a < 3; ++a) position[a] = reader.to_double(token(a), "a position coordinate");
          break;
        case Target::radius: radius = reader.to_double(token(0), "radius"); break;
        case Target::diameter: radius = 0.5 * reader.to_double(token(0), "diameter"); break;
        case Target::species:
          if (species_gives_type) species.emplace_back(token(0));
          break;
        case Target::type: type = reader.to_int(token(0), "type"); break;
        case Target::velocity:
          for (int a = 0; a < 3; ++a) velocity[a] = reader.to_double(token(a), "a velocity component");
          break;
        case Target::angular_velocity:
          for (int a = 0; a < 3; ++a)
            angular_velocity[a] = reader.to_double(token(a), "an angular velocity component");
          break;
        case Target::density: packing.density.push_back(reader.to_double(token(0), "density")); break;
        case Target::fixed: {
          const auto flag = detail::parse_flag(token(0));
          if (!flag)
            reader.fail(fmt::format("fixed flag {}: expected 0 or 1", detail::quote_token(token(0))));
          packing.fixed.push_back(*flag ? 1 : 0);
          break;
        }
        case Target::ignored: break;
        case Target::field: {
          double value = 0.0;
          if (property.kind == 'L') {
            const auto flag = detail::parse_flag(token(0));
            if (!flag)
              reader.fail(
                  fmt::format("{} = {}: expected T or F", property.name, detail::quote_token(token(0))));
            value = *flag ? 1.0 : 0.0;
          } else {
            value = reader.to_value(token(0), property.name);
          }
          packing.fields[property.field_index].values.push_back(value);
          break;
        }
      }
      column += static_cast<std::size_t>(property.count);
    }
    if (!(radius > 0.0) || !std::isfinite(radius))
      reader.fail(fmt::format("radius {:g}: must be positive and finite", radius));
    if (type < 0) reader.fail(fmt::format("type {}: must be >= 0", type));
    if (has_velocity) packing.velocity.push_back(velocity);
    if (has_angular_velocity) packing.angular_velocity.push_back(angular_velocity);
    packing.add(position, radius, type);
    lines.push_back(reader.line_number());
  }
  // What follows the particle lines: nothing, or the next frame of a trajectory (its count on a
  // line of its own). A further particle line means the count on line 1 is too small.
  while (reader.next_line()) {
    const auto tokens = detail::split(reader.line(), " \t");
    if (tokens.empty()) continue;
    if (tokens.size() == 1 && detail::parse_integer(tokens[0])) break;
    reader.fail(fmt::format("line 1 announces {} particles, but the file goes on with more lines: the count "
                            "must equal the number of particle lines (or a next frame must start with its "
                            "count)",
                            *count));
  }
  if (species_gives_type) packing.type = types_from_species(species);
  detail::finish_reading(packing, file_box, options, path, lines);
  return packing;
}

void write_xyz(const Packing& packing, const std::filesystem::path& path, const WriteOptions& options) {
  detail::validate_for_writing(packing, path);
  std::vector<std::string_view> reserved;  // a field under one of these would read back as something else
  for (const auto& known : known_properties) reserved.push_back(known.name);
  detail::check_field_names(packing, path, reserved, " \t:\"=");
  const Box box = detail::box_for_writing(packing);
  std::string header = fmt::format(
      "Lattice=\"{:.17g} 0 0 0 {:.17g} 0 0 0 {:.17g}\" Origin=\"{:.17g} {:.17g} {:.17g}\" pbc=\"{} {} {}\" "
      "Properties=species:S:1:pos:R:3:radius:R:1",
      box.length.x, box.length.y, box.length.z, box.lo.x, box.lo.y, box.lo.z, box.periodic[0] ? 'T' : 'F',
      box.periodic[1] ? 'T' : 'F', box.periodic[2] ? 'T' : 'F');
  if (!packing.velocity.empty()) header += ":velo:R:3";
  if (!packing.angular_velocity.empty()) header += ":omega:R:3";
  if (!packing.density.empty()) header += ":density:R:1";
  if (!packing.fixed.empty()) header += ":fixed:I:1";
  for (const auto& field : packing.fields) header += fmt::format(":{}:R:1", field.name);
  if (!options.comment.empty()) {
    std::string comment = detail::single_line(options.comment);
    std::replace(comment.begin(), comment.end(), '"', '\'');  // no escapes in extended XYZ values
    header += fmt::format(" Comment=\"{}\"", comment);
  }

  write_atomically(path, [&](std::ostream& out) {
    fmt::memory_buffer buffer;
    auto flush = [&] {
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      buffer.clear();
    };
    auto out_it = std::back_inserter(buffer);
    fmt::format_to(out_it, "{}\n{}\n", packing.size(), header);
    for (std::size_t k = 0; k < packing.size(); ++k) {
      const Vec3& p = packing.position[k];
      fmt::format_to(out_it, "T{} {:.17g} {:.17g} {:.17g} {:.17g}", packing.type[k], p.x, p.y, p.z,
                     packing.radius[k]);
      if (!packing.velocity.empty()) {
        const Vec3& v = packing.velocity[k];
        fmt::format_to(out_it, " {:.17g} {:.17g} {:.17g}", v.x, v.y, v.z);
      }
      if (!packing.angular_velocity.empty()) {
        const Vec3& w = packing.angular_velocity[k];
        fmt::format_to(out_it, " {:.17g} {:.17g} {:.17g}", w.x, w.y, w.z);
      }
      if (!packing.density.empty()) fmt::format_to(out_it, " {:.17g}", packing.density[k]);
      if (!packing.fixed.empty()) fmt::format_to(out_it, " {}", packing.fixed[k] ? 1 : 0);
      for (const auto& field : packing.fields) fmt::format_to(out_it, " {:.17g}", field.values[k]);
      buffer.push_back('\n');
      if (buffer.size() > (1u << 20)) flush();
    }
    flush();
  });
}

}  // namespace packlab::io
