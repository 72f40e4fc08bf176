// CSV, for spreadsheets and pandas (pandas.read_csv(path, comment='#')):
//
//   # packlab: <WriteOptions.comment>                        optional
//   # box lo 0 0 0 length 10 10 10 periodic T T F             the box (always written)
//   x,y,z,r,type                                             header row
//   1.25,3.5,0.75,0.5,0                                      one particle per row
//
// The box line names its parts, so it reads without this comment: lo = lower corner, length =
// edge lengths, periodic = T/F per axis. The reader also accepts the text format's short form
// '# box Lx Ly Lz' (lo = 0, periodic), files without a box line (bounding box, or
// ReadOptions.box), header columns in any order (x, y, z, r or radius or diameter, optional
// type), and files without a header row (x,y,z,r[,type] by position). Other '#' lines are
// comments.
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <iterator>

#include "packlab/core/error.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::io {

namespace {

enum class CsvColumn { x, y, z, radius, diameter, type };

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t begin = 0;
  while (true) {
    const auto comma = line.find(',', begin);
    std::string_view field =
        detail::trim(line.substr(begin, comma == std::string_view::npos ? line.npos : comma - begin));
    if (field.size() >= 2 && field.front() == '"' && field.back() == '"')
      field = field.substr(1, field.size() - 2);
    fields.push_back(field);
    if (comma == std::string_view::npos) break;
    begin = comma + 1;
  }
  return fields;
}

std::vector<CsvColumn> parse_header(const std::vector<std::string_view>& fields,
                                    const detail::LineReader& reader) {
  std::vector<CsvColumn> columns;
  std::array<int, 6> seen{};
  for (const auto field : fields) {
    const std::string name = detail::to_lower(field);
    CsvColumn column = CsvColumn::x;
    if (name == "x")
      column = CsvColumn::x;
    else if (name == "y")
      column = CsvColumn::y;
    else if (name == "z")
      column = CsvColumn::z;
    else if (name == "r" || name == "radius")
      column = CsvColumn::radius;
    else if (name == "d" || name == "diameter")
      column = CsvColumn::diameter;
    else if (name == "type")
      column = CsvColumn::type;
    else
      reader.fail(
          fmt::format("unknown column {}: expected x, y, z, r (or radius, diameter) and "
                      "optionally type",
                      detail::quote_token(field)));
    if (seen[static_cast<std::size_t>(column)]++)
      reader.fail(fmt::format("column {} appears twice", detail::quote_token(field)));
    columns.push_back(column);
  }
  auto has = [&](CsvColumn c) { return seen[static_cast<std::size_t>(c)] > 0; };
  if (!has(CsvColumn::x) || !has(CsvColumn::y) || !has(CsvColumn::z))
    reader.fail("header row must name columns x, y and z");
  if (has(CsvColumn::radius) == has(CsvColumn::diameter))
    reader.fail("header row must name exactly one of r (radius) and diameter");
  return columns;
}

}  // namespace

Packing read_csv(const std::filesystem::path& path, const ReadOptions& options) {
  detail::LineReader reader(path);
  Packing packing;
  std::optional<Box> file_box;
  std::vector<CsvColumn> columns;  // empty until the header row (or first data row) is seen
  std::vector<std::size_t> lines;  // of each particle
  while (reader.next_line()) {
    const std::string_view line = detail::trim(reader.line());
    if (line.empty()) continue;
    if (detail::read_comment_line(line, reader, file_box)) continue;
    const auto fields = split_fields(line);
    if (columns.empty()) {
      if (!detail::parse_double(fields.front())) {
        columns = parse_header(fields, reader);
        continue;
      }
      // No header row: the columns are x,y,z,r[,type] by position.
      if (fields.size() != 4 && fields.size() != 5)
        reader.fail(fmt::format("expected a header row or x,y,z,r[,type], got {} fields", fields.size()));
      columns = {CsvColumn::x, CsvColumn::y, CsvColumn::z, CsvColumn::radius};
      if (fields.size() == 5) columns.push_back(CsvColumn::type);
    }
    if (fields.size() != columns.size())
      reader.fail(fmt::format("expected {} comma-separated fields, got {}", columns.size(), fields.size()));
    Vec3 position;
    double radius = 0.0;
    int type = 0;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      switch (columns[c]) {
        case CsvColumn::x: position.x = reader.to_double(fields[c], "x"); break;
        case CsvColumn::y: position.y = reader.to_double(fields[c], "y"); break;
        case CsvColumn::z: position.z = reader.to_double(fields[c], "z"); break;
        case CsvColumn::radius: radius = reader.to_double(fields[c], "radius r"); break;
        case CsvColumn::diameter: radius = 0.5 * reader.to_double(fields[c], "diameter"); break;
        case CsvColumn::type: type = reader.to_int(fields[c], "type"); break;
      }
    }
    if (!(radius > 0.0) || !std::isfinite(radius))
      reader.fail(fmt::format("radius {:g}: must be positive and finite", radius));
    if (type < 0) reader.fail(fmt::format("type {}: must be >= 0", type));
    packing.add(position, radius, type);
    lines.push_back(reader.line_number());
  }
  detail::finish_reading(packing, file_box, options, path, lines);
  return packing;
}

void write_csv(const Packing& packing, const std::filesystem::path& path, const WriteOptions& options) {
  detail::validate_for_writing(packing, path);
  write_atomically(path, [&](std::ostream& out) {
    fmt::memory_buffer buffer;
    auto flush = [&] {
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      buffer.clear();
    };
    if (!options.comment.empty())
      fmt::format_to(std::back_inserter(buffer), "# packlab: {}\n", detail::single_line(options.comment));
    // Always the long form here: a CSV reader should not have to know the short one's defaults.
    fmt::format_to(std::back_inserter(buffer), "# {}\n",
                   detail::format_box_comment(detail::box_for_writing(packing), /*allow_short_form=*/false));
    fmt::format_to(std::back_inserter(buffer), "x,y,z,r,type\n");
    for (std::size_t k = 0; k < packing.size(); ++k) {
      const Vec3& p = packing.position[k];
      fmt::format_to(std::back_inserter(buffer), "{:.17g},{:.17g},{:.17g},{:.17g},{}\n", p.x, p.y, p.z,
                     packing.radius[k], packing.type[k]);
      if (buffer.size() > (1u << 20)) flush();
    }
    flush();
  });
}

}  // namespace packlab::io
