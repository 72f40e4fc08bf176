// VTK XML unstructured grid (.vtu), ASCII, for ParaView:
//
//   FieldData   box_lo (Float64 x3), box_length (Float64 x3), periodic (Int32 x3, 1 = periodic)
//   Points      particle centres (Float64, 3 components)
//   Cells       first one VTK_VERTEX (1) per particle, in particle order, then one VTK_LINE (3)
//               per bond (i, j); connectivity and offsets are Int64, types UInt8
//   PointData   radius, type, and when present velocity (3), angular_velocity (3), density,
//               fixed (Int32 0/1), then every extra field under its own name (Float64)
//   CellData    only with bonds: bond_material, bond_state (Int32), bond_rest_length (Float64),
//               bond_image (Int32, 3 components). Every cell needs a value, so the vertex cells
//               carry bond_material = bond_state = -1, bond_rest_length = -1, bond_image = 0 0 0
//               (threshold bond_state >= 0 in ParaView to keep only bonds). Bonds across a
//               periodic boundary are drawn between the two stored centres, i.e. across the box.
//   WriteOptions.comment goes into an XML comment after the declaration.
//
// The reader reads these files back exactly (17 significant digits) with the small XML parser
// of io/xml.hpp. It is not a general VTK reader: ASCII DataArrays only, one Piece, vertex and line cells only. It
// also reads ASCII files that VTK/ParaView wrote (InformationKey metadata is skipped).
// Unknown one-component PointData arrays become extra fields; unknown CellData arrays are
// ignored. Files without FieldData box get the bounding box (or ReadOptions.box).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <type_traits>
#include <unordered_set>

#include "packlab/core/error.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/xml.hpp"

namespace packlab::io {

namespace {

constexpr int vtk_vertex = 1;
constexpr int vtk_line = 3;

using detail::XmlDocument;
using detail::XmlElement;
using detail::xml_escape;

// ---------------------------------------------------------------------------------------------
// VTU reading on top of the XML tree.

class VtuReader {
 public:
  explicit VtuReader(const XmlDocument& document) : doc_(document) {}

  std::string name_of(const XmlElement& array) const {
    const std::string* name = array.attribute("Name");
    if (!name) doc_.fail_at(array.start, "<DataArray> without a Name attribute");
    return *name;
  }

  int components_of(const XmlElement& array) const {
    const std::string* text = array.attribute("NumberOfComponents");
    if (!text) return 1;
    const auto value = detail::parse_integer(*text);
    if (!value || *value < 1 || *value > 64)
      doc_.fail_at(array.start, fmt::format("NumberOfComponents={}: expected a small positive integer",
                                            detail::quote_token(*text)));
    return static_cast<int>(*value);
  }

  std::size_t count_attribute(const XmlElement& element, std::string_view key) const {
    const std::string* text = element.attribute(key);
    if (!text) doc_.fail_at(element.start, fmt::format("<{}> has no {} attribute", element.name, key));
    const auto value = detail::parse_integer(*text);
    if (!value || *value < 0 || *value > std::numeric_limits<int>::max())
      doc_.fail_at(element.start,
                   fmt::format("{}={}: expected a non-negative integer", key, detail::quote_token(*text)));
    return static_cast<std::size_t>(*value);
  }

  // Calls `take(token, offset)` for each whitespace-separated token of an ASCII DataArray and
  // checks that there are exactly `expected` of them.
  template <typename Take>
  void for_each_token(const XmlElement& array, std::size_t expected, Take&& take) const {
    const std::string* format = array.attribute("format");
    if (format && *format != "ascii")
      doc_.fail_at(array.start, fmt::format("DataArray {} has format=\"{}\": only ascii is supported",
                                            detail::quote_token(name_or_unnamed(array)), *format));
    // The numbers are the text outside child elements: VTK's own writer puts <InformationKey>
    // metadata (ranges) inside DataArrays.
    std::vector<std::pair<std::size_t, std::size_t>> segments;  // [begin, end) offsets in the file
    std::size_t segment_begin = array.content_begin;
    for (const std::size_t c : array.children) {
      const XmlElement& child = doc_.element(c);
      if (child.name != "InformationKey")
        doc_.fail_at(child.start, fmt::format("<{}> inside a DataArray: expected only numbers", child.name));
      segments.emplace_back(segment_begin, child.start);
      segment_begin = child.end;
    }
    segments.emplace_back(segment_begin, array.content_end);
    std::size_t count = 0;
    for (const auto& [begin, end_of_segment] : segments) {
      const std::string_view content = doc_.text().substr(begin, end_of_segment - begin);
      std::size_t pos = 0;
      while (true) {
        pos = content.find_first_not_of(" \t\r\n", pos);
        if (pos == std::string_view::npos) break;
        std::size_t end = content.find_first_of(" \t\r\n", pos);
        if (end == std::string_view::npos) end = content.size();
        if (count == expected)
          doc_.fail_at(begin + pos, fmt::format("DataArray {} has more than the {} values expected",
                                                detail::quote_token(name_or_unnamed(array)), expected));
        take(content.substr(pos, end - pos), begin + pos);
        ++count;
        pos = end;
      }
    }
    if (count != expected)
      doc_.fail_at(array.start, fmt::format("DataArray {} has {} values, expected {} (truncated file?)",
                                            detail::quote_token(name_or_unnamed(array)), count, expected));
  }

  // Finite numbers only (coordinates, radii, box, velocities, ...); `any_number` for extra fields,
  // where nan marks a missing value.
  enum class Numbers { finite, any_number };
  std::vector<double> doubles(const XmlElement& array, std::size_t expected,
                              Numbers allowed = Numbers::finite) const {
    std::vector<double> values;
    for_each_token(array, expected, [&](std::string_view token, std::size_t offset) {
      const auto value = detail::parse_double(token);
      if (!value)
        doc_.fail_at(offset,
                     fmt::format("expected a number in DataArray {}, got {}",
                                 detail::quote_token(name_or_unnamed(array)), detail::quote_token(token)));
      if (allowed == Numbers::finite && !std::isfinite(*value))
        doc_.fail_at(offset, fmt::format("value {} in DataArray {}: must be a finite number",
                                         detail::quote_token(token), detail::quote_token(name_or_unnamed(array))));
      values.push_back(*value);
    });
    return values;
  }

  std::vector<long long> integers(const XmlElement& array, std::size_t expected, long long min,
                                  long long max) const {
    std::vector<long long> values;
    for_each_token(array, expected, [&](std::string_view token, std::size_t offset) {
      const auto value = detail::parse_integer(token);
      if (!value || *value < min || *value > max)
        doc_.fail_at(offset,
                     fmt::format("expected an integer in [{}, {}] in DataArray {}, got {}", min, max,
                                 detail::quote_token(name_or_unnamed(array)), detail::quote_token(token)));
      values.push_back(*value);
    });
    return values;
  }

  // The DataArrays inside `parent`, each with a unique Name.
  std::vector<const XmlElement*> named_arrays(const XmlElement& parent) const {
    auto arrays = doc_.children(parent, "DataArray");
    std::unordered_set<std::string_view> names;  // views of the attribute values held by doc_
    for (const XmlElement* array : arrays) {
      const std::string* name = array->attribute("Name");
      if (!name) doc_.fail_at(array->start, "<DataArray> without a Name attribute");
      if (!names.insert(*name).second)
        doc_.fail_at(array->start, fmt::format("second DataArray named {}", detail::quote_token(*name)));
    }
    return arrays;
  }

  void require_components(const XmlElement& array, int components) const {
    if (components_of(array) != components)
      doc_.fail_at(array.start,
                   fmt::format("DataArray {} has {} components, expected {}",
                               detail::quote_token(name_of(array)), components_of(array), components));
  }

  const XmlDocument& doc() const { return doc_; }

 private:
  std::string name_or_unnamed(const XmlElement& array) const {
    const std::string* name = array.attribute("Name");
    return name ? *name : std::string("(unnamed)");
  }

  const XmlDocument& doc_;
};

constexpr int int_max = std::numeric_limits<int>::max();

std::vector<Vec3> to_vec3(const std::vector<double>& flat) {
  std::vector<Vec3> out(flat.size() / 3);
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = {flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]};
  return out;
}

std::optional<Box> read_field_data_box(const VtuReader& vtu, const XmlElement& grid) {
  const XmlElement* field_data = vtu.doc().child(grid, "FieldData");
  if (!field_data) return std::nullopt;
  const XmlElement *lo = nullptr, *length = nullptr, *periodic = nullptr;
  for (const XmlElement* array : vtu.named_arrays(*field_data)) {
    const std::string name = vtu.name_of(*array);
    if (name == "box_lo")
      lo = array;
    else if (name == "box_length")
      length = array;
    else if (name == "periodic")
      periodic = array;
  }
  if (!lo && !length && !periodic) return std::nullopt;
  if (!lo || !length || !periodic)
    vtu.doc().fail_at(field_data->start, "FieldData needs all of box_lo, box_length and periodic, or none");
  Box box;
  const auto lo_values = vtu.doubles(*lo, 3);
  const auto length_values = vtu.doubles(*length, 3);
  const auto periodic_values = vtu.integers(*periodic, 3, 0, 1);
  for (int a = 0; a < 3; ++a) {
    const auto k = static_cast<std::size_t>(a);
    box.lo[a] = lo_values[k];
    box.length[a] = length_values[k];
    box.periodic[k] = periodic_values[k] == 1;
  }
  return box;
}

void read_point_data(const VtuReader& vtu, const XmlElement& piece, std::size_t n, Packing& packing) {
  const XmlElement* point_data = vtu.doc().child(piece, "PointData");
  if (!point_data)
    vtu.doc().fail_at(piece.start, "<Piece> has no <PointData>: expected at least a radius array");
  bool have_radius = false;
  packing.type.assign(n, 0);
  for (const XmlElement* array : vtu.named_arrays(*point_data)) {
    const std::string name = vtu.name_of(*array);
    if (name == "radius") {
      vtu.require_components(*array, 1);
      packing.radius = vtu.doubles(*array, n);
      have_radius = true;
    } else if (name == "type") {
      vtu.require_components(*array, 1);
      const auto types = vtu.integers(*array, n, 0, int_max);
      std::transform(types.begin(), types.end(), packing.type.begin(),
                     [](long long t) { return static_cast<int>(t); });
    } else if (name == "velocity") {
      vtu.require_components(*array, 3);
      packing.velocity = to_vec3(vtu.doubles(*array, 3 * n));
    } else if (name == "angular_velocity") {
      vtu.require_components(*array, 3);
      packing.angular_velocity = to_vec3(vtu.doubles(*array, 3 * n));
    } else if (name == "density") {
      vtu.require_components(*array, 1);
      packing.density = vtu.doubles(*array, n);
    } else if (name == "fixed") {
      vtu.require_components(*array, 1);
      const auto flags = vtu.integers(*array, n, 0, 1);
      packing.fixed.assign(flags.begin(), flags.end());
    } else if (vtu.components_of(*array) == 1) {
      packing.fields.push_back({name, vtu.doubles(*array, n, VtuReader::Numbers::any_number)});
    } else {
      vtu.doc().fail_at(array->start, fmt::format("PointData array {} has {} components: only one-component "
                                                  "extra arrays are supported",
                                                  detail::quote_token(name), vtu.components_of(*array)));
    }
  }
  if (!have_radius) vtu.doc().fail_at(point_data->start, "<PointData> has no radius array");
  for (std::size_t k = 0; k < n; ++k)
    if (!(packing.radius[k] > 0.0) || !std::isfinite(packing.radius[k]))
      vtu.doc().fail_at(
          point_data->start,
          fmt::format("radius of point {} = {:g}: must be positive and finite", k, packing.radius[k]));
}

void read_cells(const VtuReader& vtu, const XmlElement& piece, std::size_t n, std::size_t cell_count,
                Packing& packing) {
  const XmlDocument& doc = vtu.doc();
  const XmlElement& cells = doc.required_child(piece, "Cells");
  const XmlElement *connectivity_array = nullptr, *offsets_array = nullptr, *types_array = nullptr;
  for (const XmlElement* array : vtu.named_arrays(cells)) {
    const std::string name = vtu.name_of(*array);
    if (name == "connectivity")
      connectivity_array = array;
    else if (name == "offsets")
      offsets_array = array;
    else if (name == "types")
      types_array = array;
  }
  if (!connectivity_array || !offsets_array || !types_array)
    doc.fail_at(cells.start, "<Cells> needs the DataArrays connectivity, offsets and types");
  const auto offsets = vtu.integers(*offsets_array, cell_count, 0, std::numeric_limits<long long>::max() / 2);
  const auto types = vtu.integers(*types_array, cell_count, 0, 255);
  const std::size_t connectivity_size = cell_count == 0 ? 0 : static_cast<std::size_t>(offsets.back());
  if (connectivity_size > 2 * cell_count)
    doc.fail_at(offsets_array->start,
                "offsets imply more than two points per cell: only vertices and lines are supported");
  const auto connectivity =
      vtu.integers(*connectivity_array, connectivity_size, 0, n == 0 ? -1 : static_cast<long long>(n) - 1);

  // Bond attributes, one value per cell.
  const XmlElement* cell_data = doc.child(piece, "CellData");
  std::vector<long long> material, state;
  std::vector<double> rest_length;
  std::vector<long long> image;
  auto bond_arrays_read = [&] {
    if (!cell_data) doc.fail_at(piece.start, "line cells (bonds) without <CellData>");
    const XmlElement *m = nullptr, *s = nullptr, *r = nullptr, *i = nullptr;
    for (const XmlElement* array : vtu.named_arrays(*cell_data)) {
      const std::string name = vtu.name_of(*array);
      if (name == "bond_material")
        m = array;
      else if (name == "bond_state")
        s = array;
      else if (name == "bond_rest_length")
        r = array;
      else if (name == "bond_image")
        i = array;
    }
    if (!m || !s || !r || !i)
      doc.fail_at(
          cell_data->start,
          "line cells (bonds) need CellData bond_material, bond_state, bond_rest_length and bond_image");
    vtu.require_components(*i, 3);
    material = vtu.integers(*m, cell_count, std::numeric_limits<int>::min(), int_max);
    state = vtu.integers(*s, cell_count, std::numeric_limits<int>::min(), int_max);
    rest_length = vtu.doubles(*r, cell_count);
    image = vtu.integers(*i, 3 * cell_count, std::numeric_limits<int>::min(), int_max);
  };

  long long previous_end = 0;
  for (std::size_t c = 0; c < cell_count; ++c) {
    const long long end = offsets[c];
    const long long size = end - previous_end;
    if (end > static_cast<long long>(connectivity.size()))
      doc.fail_at(offsets_array->start,
                  fmt::format("offset {} of cell {} is past the end of connectivity", end, c));
    const bool vertex = types[c] == vtk_vertex && size == 1;
    const bool line = types[c] == vtk_line && size == 2;
    if (!vertex && !line)
      doc.fail_at(types_array->start,
                  fmt::format("cell {} has type {} and {} points: only vertices (type 1, one "
                              "point) and lines (type 3, two points) are supported",
                              c, types[c], size));
    if (line) {
      if (material.empty()) bond_arrays_read();
      const auto first = static_cast<std::size_t>(previous_end);
      packing.bonds.add(static_cast<int>(connectivity[first]), static_cast<int>(connectivity[first + 1]),
                        {static_cast<int>(image[3 * c]), static_cast<int>(image[3 * c + 1]),
                         static_cast<int>(image[3 * c + 2])},
                        static_cast<int>(material[c]), rest_length[c], static_cast<int>(state[c]));
    }
    previous_end = end;
  }
}

}  // namespace

Packing read_vtu(const std::filesystem::path& path, const ReadOptions& options) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail_input(fmt::format("{}: no such file", path.string()));
  if (std::filesystem::is_directory(path, ec))
    fail_input(fmt::format("{}: is a folder, expected a file", path.string()));
  std::ifstream in(path, std::ios::binary);
  if (!in) fail_input(fmt::format("{}: cannot open the file for reading", path.string()));
  std::ostringstream contents;
  contents << in.rdbuf();
  if (in.bad()) fail_input(fmt::format("{}: read error", path.string()));

  const XmlDocument doc(std::move(contents).str(), path);
  const VtuReader vtu(doc);
  const XmlElement& root = doc.root();
  const std::string* file_type = root.attribute("type");
  if (root.name != "VTKFile" || !file_type || *file_type != "UnstructuredGrid")
    doc.fail_at(root.start, "expected <VTKFile type=\"UnstructuredGrid\">");
  const XmlElement& grid = doc.required_child(root, "UnstructuredGrid");
  const auto pieces = doc.children(grid, "Piece");
  if (pieces.size() != 1)
    doc.fail_at(grid.start, fmt::format("expected one <Piece>, found {}", pieces.size()));
  const XmlElement& piece = *pieces.front();
  const std::size_t n = vtu.count_attribute(piece, "NumberOfPoints");
  const std::size_t cell_count = vtu.count_attribute(piece, "NumberOfCells");

  Packing packing;
  const XmlElement& points = doc.required_child(piece, "Points");
  const auto point_arrays = doc.children(points, "DataArray");
  if (point_arrays.size() != 1) doc.fail_at(points.start, "<Points> needs exactly one DataArray");
  if (vtu.components_of(*point_arrays.front()) != 3)
    doc.fail_at(point_arrays.front()->start, "the Points DataArray needs NumberOfComponents=\"3\"");
  packing.position = to_vec3(vtu.doubles(*point_arrays.front(), 3 * n));
  read_point_data(vtu, piece, n, packing);
  read_cells(vtu, piece, n, cell_count, packing);
  detail::finish_reading(packing, read_field_data_box(vtu, grid), options, path);
  return packing;
}

void write_vtu(const Packing& packing, const std::filesystem::path& path, const WriteOptions& options) {
  detail::validate_for_writing(packing, path);
  detail::check_field_names(packing, path,
                            {"radius", "type", "velocity", "angular_velocity", "density", "fixed"}, "");
  const std::size_t n = packing.size();
  const std::size_t bond_count = packing.bonds.size();
  const Box box = detail::box_for_writing(packing);

  write_atomically(path, [&](std::ostream& out) {
    fmt::memory_buffer buffer;
    auto it = std::back_inserter(buffer);
    auto flush_if_large = [&] {
      if (buffer.size() < (1u << 20)) return;
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      buffer.clear();
    };
    auto open_array = [&](std::string_view type, std::string_view name, int components) {
      fmt::format_to(it, "        <DataArray type=\"{}\" Name=\"{}\"", type, xml_escape(name));
      if (components != 1) fmt::format_to(it, " NumberOfComponents=\"{}\"", components);
      fmt::format_to(it, " format=\"ascii\">\n");
    };
    auto close_array = [&] { fmt::format_to(it, "        </DataArray>\n"); };
    auto scalar_array = [&](std::string_view type, std::string_view name, std::size_t count, auto value_at) {
      open_array(type, name, 1);
      for (std::size_t k = 0; k < count; ++k) {
        if constexpr (std::is_floating_point_v<decltype(value_at(k))>)
          fmt::format_to(it, "{:.17g}\n", value_at(k));
        else
          fmt::format_to(it, "{}\n", value_at(k));
        flush_if_large();
      }
      close_array();
    };
    auto vector_array = [&](std::string_view name, const std::vector<Vec3>& values) {
      open_array("Float64", name, 3);
      for (const Vec3& v : values) {
        fmt::format_to(it, "{:.17g} {:.17g} {:.17g}\n", v.x, v.y, v.z);
        flush_if_large();
      }
      close_array();
    };

    fmt::format_to(it, "<?xml version=\"1.0\"?>\n");
    if (!options.comment.empty()) {
      std::string comment = detail::single_line(options.comment);
      // "--" may not appear inside an XML comment.
      for (auto at = comment.find("--"); at != std::string::npos; at = comment.find("--"))
        comment.replace(at, 2, "- -");
      if (!comment.empty() && comment.back() == '-') comment += ' ';
      fmt::format_to(it, "<!-- packlab: {} -->\n", comment);
    }
    fmt::format_to(it,
                   "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
                   "header_type=\"UInt64\">\n");
    fmt::format_to(it, "  <UnstructuredGrid>\n    <FieldData>\n");
    fmt::format_to(
        it,
        "      <DataArray type=\"Float64\" Name=\"box_lo\" NumberOfTuples=\"3\" format=\"ascii\">\n"
        "        {:.17g} {:.17g} {:.17g}\n      </DataArray>\n",
        box.lo.x, box.lo.y, box.lo.z);
    fmt::format_to(
        it,
        "      <DataArray type=\"Float64\" Name=\"box_length\" NumberOfTuples=\"3\" format=\"ascii\">\n"
        "        {:.17g} {:.17g} {:.17g}\n      </DataArray>\n",
        box.length.x, box.length.y, box.length.z);
    fmt::format_to(
        it,
        "      <DataArray type=\"Int32\" Name=\"periodic\" NumberOfTuples=\"3\" format=\"ascii\">\n"
        "        {:d} {:d} {:d}\n      </DataArray>\n",
        box.periodic[0] ? 1 : 0, box.periodic[1] ? 1 : 0, box.periodic[2] ? 1 : 0);
    fmt::format_to(it, "    </FieldData>\n    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n,
                   n + bond_count);

    fmt::format_to(it, "      <PointData Scalars=\"radius\">\n");
    scalar_array("Float64", "radius", n, [&](std::size_t k) { return packing.radius[k]; });
    scalar_array("Int32", "type", n, [&](std::size_t k) { return packing.type[k]; });
    if (!packing.velocity.empty()) vector_array("velocity", packing.velocity);
    if (!packing.angular_velocity.empty()) vector_array("angular_velocity", packing.angular_velocity);
    if (!packing.density.empty())
      scalar_array("Float64", "density", n, [&](std::size_t k) { return packing.density[k]; });
    if (!packing.fixed.empty())
      scalar_array("Int32", "fixed", n, [&](std::size_t k) { return packing.fixed[k] ? 1 : 0; });
    for (const auto& field : packing.fields)
      scalar_array("Float64", field.name, n, [&](std::size_t k) { return field.values[k]; });
    fmt::format_to(it, "      </PointData>\n");

    if (bond_count > 0) {
      const Bonds& bonds = packing.bonds;
      fmt::format_to(it, "      <CellData>\n");
      scalar_array("Int32", "bond_material", n + bond_count,
                   [&](std::size_t c) { return c < n ? -1 : bonds.material[c - n]; });
      scalar_array("Int32", "bond_state", n + bond_count,
                   [&](std::size_t c) { return c < n ? -1 : bonds.state[c - n]; });
      scalar_array("Float64", "bond_rest_length", n + bond_count,
                   [&](std::size_t c) { return c < n ? -1.0 : bonds.rest_length[c - n]; });
      open_array("Int32", "bond_image", 3);
      for (std::size_t c = 0; c < n + bond_count; ++c) {
        const std::array<int, 3> image = c < n ? std::array<int, 3>{0, 0, 0} : bonds.image[c - n];
        fmt::format_to(it, "{} {} {}\n", image[0], image[1], image[2]);
        flush_if_large();
      }
      close_array();
      fmt::format_to(it, "      </CellData>\n");
    }

    fmt::format_to(it, "      <Points>\n");
    vector_array("Points", packing.position);
    fmt::format_to(it, "      </Points>\n      <Cells>\n");
    open_array("Int64", "connectivity", 1);
    for (std::size_t k = 0; k < n; ++k) {
      fmt::format_to(it, "{}\n", k);
      flush_if_large();
    }
    for (std::size_t b = 0; b < bond_count; ++b) {
      fmt::format_to(it, "{} {}\n", packing.bonds.i[b], packing.bonds.j[b]);
      flush_if_large();
    }
    close_array();
    open_array("Int64", "offsets", 1);
    for (std::size_t k = 0; k < n; ++k) {
      fmt::format_to(it, "{}\n", k + 1);
      flush_if_large();
    }
    for (std::size_t b = 0; b < bond_count; ++b) {
      fmt::format_to(it, "{}\n", n + 2 * (b + 1));
      flush_if_large();
    }
    close_array();
    open_array("UInt8", "types", 1);
    for (std::size_t c = 0; c < n + bond_count; ++c) {
      fmt::format_to(it, "{}\n", c < n ? vtk_vertex : vtk_line);
      flush_if_large();
    }
    close_array();
    fmt::format_to(it, "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
  });
}

}  // namespace packlab::io
