// Format dispatch by extension, the bounding box, and the parsing helpers every reader shares
// (so that all formats report errors as "<file>:<line>: <what was expected>").
#include "packlab/io/packing_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "packlab/core/error.hpp"

namespace packlab::io {

namespace {

struct ExtensionFormat {
  const char* extension;
  Format format;
};

constexpr ExtensionFormat known_extensions[] = {
    {".xyz", Format::xyz},
    {".extxyz", Format::xyz},
    {".vtu", Format::vtu},
    {".data", Format::lammps_data},
    {".lmp", Format::lammps_data},
    {".dump", Format::lammps_dump},
    {".lammpstrj", Format::lammps_dump},
    {".csv", Format::csv},
    {".txt", Format::text},
    {".dat", Format::text},
};

}  // namespace

Format format_from_path(const std::filesystem::path& path) {
  const std::string extension = detail::to_lower(path.extension().string());
  for (const auto& known : known_extensions)
    if (extension == known.extension) return known.format;
  // LAMMPS habitually names files "data.<name>" and "dump.<name>".
  const std::string filename = detail::to_lower(path.filename().string());
  if (filename.starts_with("data.")) return Format::lammps_data;
  if (filename.starts_with("dump.")) return Format::lammps_dump;
  std::string list;
  for (const auto& known : known_extensions) list += fmt::format(" {}", known.extension);
  fail_input(fmt::format("{}: unknown file extension '{}': expected one of{}", path.string(),
                         path.extension().string(), list));
}

std::string format_name(Format format) {
  switch (format) {
    case Format::xyz: return "xyz";
    case Format::vtu: return "vtu";
    case Format::lammps_data: return "lammps-data";
    case Format::lammps_dump: return "lammps-dump";
    case Format::csv: return "csv";
    case Format::text: return "text";
  }
  throw std::logic_error("format_name: unhandled Format value");
}

Packing read_packing(const std::filesystem::path& path, const ReadOptions& options) {
  switch (format_from_path(path)) {
    case Format::xyz: return read_xyz(path, options);
    case Format::vtu: return read_vtu(path, options);
    case Format::lammps_data: return read_lammps_data(path, options);
    case Format::lammps_dump: return read_lammps_dump(path, options);
    case Format::csv: return read_csv(path, options);
    case Format::text: return read_text(path, options);
  }
  throw std::logic_error("read_packing: unhandled Format value");
}

void write_packing(const Packing& packing, const std::filesystem::path& path, const WriteOptions& options) {
  switch (format_from_path(path)) {
    case Format::xyz: return write_xyz(packing, path, options);
    case Format::vtu: return write_vtu(packing, path, options);
    case Format::lammps_data: return write_lammps_data(packing, path, options);
    case Format::lammps_dump:
      fail_input(
          fmt::format("cannot write {}: LAMMPS dump files are read-only here; write a LAMMPS "
                      "data file (.data) instead",
                      path.string()));
    case Format::csv: return write_csv(packing, path, options);
    case Format::text: return write_text(packing, path, options);
  }
  throw std::logic_error("write_packing: unhandled Format value");
}

Box bounding_box(const Packing& packing) {
  Box box;
  box.periodic = {false, false, false};
  if (packing.size() == 0) {
    box.length = {0.0, 0.0, 0.0};
    return box;
  }
  constexpr double inf = std::numeric_limits<double>::infinity();
  Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  for (std::size_t k = 0; k < packing.size(); ++k) {
    const double r = k < packing.radius.size() ? packing.radius[k] : 0.0;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], packing.position[k][a] - r);
      hi[a] = std::max(hi[a], packing.position[k][a] + r);
    }
  }
  box.lo = lo;
  box.length = hi - lo;
  return box;
}

namespace detail {

LineReader::LineReader(const std::filesystem::path& path) : path_(path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail_input(fmt::format("{}: no such file", path.string()));
  if (std::filesystem::is_directory(path, ec))
    fail_input(fmt::format("{}: is a folder, expected a file", path.string()));
  stream_.open(path, std::ios::binary);
  if (!stream_) fail_input(fmt::format("{}: cannot open the file for reading", path.string()));
}

bool LineReader::next_line() {
  if (!std::getline(stream_, line_)) {
    if (stream_.bad()) fail_input(fmt::format("{}: read error after line {}", path_.string(), line_number_));
    return false;
  }
  ++line_number_;
  if (!line_.empty() && line_.back() == '\r') line_.pop_back();
  return true;
}

void LineReader::fail(std::string_view message) const {
  fail_input(fmt::format("{}:{}: {}", path_.string(), line_number_, message));
}

void LineReader::fail_end_of_file(std::string_view expected) const {
  fail_input(fmt::format("{}: file ends after line {}: expected {} (truncated file?)", path_.string(),
                         line_number_, expected));
}

double LineReader::to_double(std::string_view token, std::string_view what) const {
  const auto value = parse_double(token);
  if (!value) fail(fmt::format("expected {} (a number), got {}", what, quote_token(token)));
  if (!std::isfinite(*value)) fail(fmt::format("{} = {}: must be a finite number", what, quote_token(token)));
  return *value;
}

double LineReader::to_value(std::string_view token, std::string_view what) const {
  if (auto value = parse_double(token)) return *value;
  fail(fmt::format("expected {} (a number), got {}", what, quote_token(token)));
}

int LineReader::to_int(std::string_view token, std::string_view what) const {
  const auto value = parse_integer(token);
  if (value && *value >= std::numeric_limits<int>::min() && *value <= std::numeric_limits<int>::max())
    return static_cast<int>(*value);
  fail(fmt::format("expected {} (an integer), got {}", what, quote_token(token)));
}

std::optional<double> parse_double(std::string_view token) {
  if (token.size() > 1 && token.front() == '+' && token[1] != '-') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  const char* end = token.data() + token.size();
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ptr != end) return std::nullopt;
  if (ec == std::errc()) return value;
  if (ec != std::errc::result_out_of_range) return std::nullopt;
  // from_chars reports subnormal results as out of range; strtod returns them (or 0) and only
  // overflow is a real error, since a writer may well have written a subnormal velocity.
  const std::string copy(token);
  char* strtod_end = nullptr;
  errno = 0;
  const double fallback = std::strtod(copy.c_str(), &strtod_end);
  if (strtod_end != copy.c_str() + copy.size() || std::isinf(fallback)) return std::nullopt;
  return fallback;
}

std::optional<long long> parse_integer(std::string_view token) {
  if (token.size() > 1 && token.front() == '+' && token[1] != '-') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  const char* end = token.data() + token.size();
  long long value = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

std::optional<bool> parse_flag(std::string_view token) {
  const std::string lower = to_lower(token);
  if (lower == "t" || lower == "1" || lower == "true") return true;
  if (lower == "f" || lower == "0" || lower == "false") return false;
  return std::nullopt;
}

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

std::vector<std::string_view> split(std::string_view text, std::string_view separators) {
  std::vector<std::string_view> tokens;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const auto begin = text.find_first_not_of(separators, pos);
    if (begin == std::string_view::npos) break;
    auto end = text.find_first_of(separators, begin);
    if (end == std::string_view::npos) end = text.size();
    tokens.push_back(text.substr(begin, end - begin));
    pos = end;
  }
  return tokens;
}

std::string to_lower(std::string_view text) {
  std::string lower(text);
  for (char& c : lower)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return lower;
}

std::string quote_token(std::string_view token) {
  constexpr std::size_t max_shown = 40;
  std::string shown;
  for (std::size_t k = 0; k < token.size() && k < max_shown; ++k) {
    const auto c = static_cast<unsigned char>(token[k]);
    shown += (c >= 0x20 && c < 0x7f) ? token[k] : '?';
  }
  if (token.size() > max_shown) shown += "...";
  return "'" + shown + "'";
}

std::string single_line(std::string_view text) {
  std::string line(text);
  for (char& c : line)
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  return line;
}

std::optional<Box> parse_box_comment(std::string_view comment, const LineReader& reader) {
  const auto tokens = split(comment, " \t,");
  if (tokens.empty() || to_lower(tokens[0]) != "box") return std::nullopt;
  Box box;
  if (tokens.size() == 4) {  // box Lx Ly Lz
    for (int a = 0; a < 3; ++a) box.length[a] = reader.to_double(tokens[1 + a], "box length");
    return box;
  }
  const bool long_form = tokens.size() == 13 && to_lower(tokens[1]) == "lo" &&
                         to_lower(tokens[5]) == "length" && to_lower(tokens[9]) == "periodic";
  if (!long_form) reader.fail("expected '# box Lx Ly Lz' or '# box lo X Y Z length Lx Ly Lz periodic T T T'");
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = reader.to_double(tokens[2 + a], "box lo");
    box.length[a] = reader.to_double(tokens[6 + a], "box length");
    const auto flag = parse_flag(tokens[10 + a]);
    if (!flag)
      reader.fail(fmt::format("expected a periodic flag (T or F), got {}", quote_token(tokens[10 + a])));
    box.periodic[a] = *flag;
  }
  return box;
}

bool read_comment_line(std::string_view line, const LineReader& reader, std::optional<Box>& box) {
  if (line.empty() || line.front() != '#') return false;
  if (auto b = parse_box_comment(line.substr(1), reader)) {
    if (box) reader.fail("second '# box' line: a file holds one box");
    box = b;
  }
  return true;
}

std::string format_box_comment(const Box& box, bool allow_short_form) {
  if (allow_short_form && box.lo == Vec3{0.0, 0.0, 0.0} &&
      box.periodic == std::array<bool, 3>{true, true, true})
    return fmt::format("box {:.17g} {:.17g} {:.17g}", box.length.x, box.length.y, box.length.z);
  return fmt::format("box lo {:.17g} {:.17g} {:.17g} length {:.17g} {:.17g} {:.17g} periodic {} {} {}",
                     box.lo.x, box.lo.y, box.lo.z, box.length.x, box.length.y, box.length.z,
                     box.periodic[0] ? 'T' : 'F', box.periodic[1] ? 'T' : 'F', box.periodic[2] ? 'T' : 'F');
}

void validate_for_writing(const Packing& packing, const std::filesystem::path& path) {
  try {
    packing.validate();
  } catch (const InputError& error) {
    fail_input(fmt::format("cannot write {}: {}", path.string(), error.what()));
  }
}

void check_field_names(const Packing& packing, const std::filesystem::path& path,
                       const std::vector<std::string_view>& reserved, std::string_view forbidden) {
  for (std::size_t f = 0; f < packing.fields.size(); ++f) {
    const std::string& name = packing.fields[f].name;
    auto reject = [&](std::string_view why) {
      fail_input(fmt::format("cannot write {}: field name {} {}", path.string(), quote_token(name), why));
    };
    if (name.empty()) reject("is empty");
    if (name.find_first_of(forbidden) != std::string::npos ||
        std::any_of(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; }))
      reject(fmt::format("contains one of the characters {} or a control character", quote_token(forbidden)));
    const std::string lower = to_lower(name);
    for (const auto own : reserved)
      if (lower == to_lower(own)) reject("is a name the format uses itself");
    for (std::size_t g = 0; g < f; ++g)
      if (packing.fields[g].name == name) reject("appears twice");
  }
}

void finish_reading(Packing& packing, const std::optional<Box>& file_box, const ReadOptions& options,
                    const std::filesystem::path& path, const std::vector<std::size_t>& lines) {
  if (options.box) {
    packing.box = *options.box;
  } else if (file_box) {
    packing.box = *file_box;
  } else {
    if (packing.size() == 0)
      fail_input(fmt::format("{}: the file has neither particles nor a box; pass a box", path.string()));
    packing.box = bounding_box(packing);
  }
  try {
    packing.validate();
  } catch (const InputError& error) {
    fail_input(fmt::format("{}: {}", path.string(), error.what()));
  }
  if (const auto outside = first_outside_open_box(packing)) {
    const Box& box = packing.box;
    const std::size_t k = outside->particle;
    const int axis = outside->axis;
    const Vec3& p = packing.position[k];
    const double r = packing.radius[k];
    const std::string where =
        lines.size() == packing.size() ? fmt::format("{}:{}", path.string(), lines[k]) : path.string();
    fail_input(fmt::format(
        "{}: particle {} lies outside the open box along {}: {} = {:.17g}, radius {:.17g}, box [{:.17g}, "
        "{:.17g}]; a particle may stick out of an open side by at most its radius + {:g} of the box edge "
        "(make the axis periodic, or give a box that holds every particle)",
        where, k, "xyz"[axis], "xyz"[axis], p[axis], r, box.lo[axis], box.hi()[axis], open_box_tolerance));
  }
}

std::optional<OutsideOpenBox> first_outside_open_box(const Packing& packing) {
  const Box& box = packing.box;
  for (std::size_t k = 0; k < packing.size(); ++k)
    for (int a = 0; a < 3; ++a) {
      if (box.periodic[static_cast<std::size_t>(a)]) continue;
      const double slack = packing.radius[k] + open_box_tolerance * box.length[a];
      const double x = packing.position[k][a];
      if (x < box.lo[a] - slack || x > box.lo[a] + box.length[a] + slack) return OutsideOpenBox{k, a};
    }
  return std::nullopt;
}

Box box_for_writing(const Packing& packing) {
  Box box = packing.box;
  if (!first_outside_open_box(packing)) return box;
  const Box spheres = bounding_box(packing);
  for (int a = 0; a < 3; ++a) {
    if (box.periodic[static_cast<std::size_t>(a)]) continue;
    const double lo = std::min(box.lo[a], spheres.lo[a]);
    const double hi = std::max(box.lo[a] + box.length[a], spheres.lo[a] + spheres.length[a]);
    box.lo[a] = lo;
    box.length[a] = hi - lo;
  }
  return box;
}

}  // namespace detail

}  // namespace packlab::io
