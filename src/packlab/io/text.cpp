// Plain text, the format of PackingGeneration and ../shared/data/anchor-packings:
//
//   # box Lx Ly Lz                 optional; lo = 0, periodic on every axis
//   x y z r                        one particle per line
//
// Lines may carry a fifth column, the particle type (0 when absent). The writer keeps the
// four-column form whenever every type is 0, and the short box line whenever the box starts at
// 0 and is periodic on every axis, so such packings stay readable by tools that know only the
// original format. Other boxes are written as
//   # box lo X Y Z length Lx Ly Lz periodic T T F
// Other lines starting with '#' are comments; the writer puts WriteOptions.comment on a
// '# packlab: ...' line, so a comment can never be mistaken for the box line.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "packlab/core/error.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::io {

Packing read_text(const std::filesystem::path& path, const ReadOptions& options) {
  detail::LineReader reader(path);
  Packing packing;
  std::optional<Box> file_box;
  std::vector<std::size_t> lines;  // of each particle
  while (reader.next_line()) {
    const std::string_view line = detail::trim(reader.line());
    if (line.empty()) continue;
    if (detail::read_comment_line(line, reader, file_box)) continue;
    const auto tokens = detail::split(line);
    if (tokens.size() != 4 && tokens.size() != 5)
      reader.fail(fmt::format("expected 'x y z r' or 'x y z r type', got {} columns", tokens.size()));
    const Vec3 position{reader.to_double(tokens[0], "x"), reader.to_double(tokens[1], "y"),
                        reader.to_double(tokens[2], "z")};
    const double radius = reader.to_double(tokens[3], "radius r");
    if (!(radius > 0.0) || !std::isfinite(radius))
      reader.fail(fmt::format("radius {:g}: must be positive and finite", radius));
    const int type = tokens.size() == 5 ? reader.to_int(tokens[4], "type") : 0;
    if (type < 0) reader.fail(fmt::format("type {}: must be >= 0", type));
    packing.add(position, radius, type);
    lines.push_back(reader.line_number());
  }
  detail::finish_reading(packing, file_box, options, path, lines);
  return packing;
}

void write_text(const Packing& packing, const std::filesystem::path& path, const WriteOptions& options) {
  detail::validate_for_writing(packing, path);
  const bool with_type = std::any_of(packing.type.begin(), packing.type.end(), [](int t) { return t != 0; });
  write_atomically(path, [&](std::ostream& out) {
    fmt::memory_buffer buffer;
    auto flush = [&] {
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      buffer.clear();
    };
    // The box line comes first: PackingGeneration-style readers expect it on line 1.
    fmt::format_to(std::back_inserter(buffer), "# {}\n",
                   detail::format_box_comment(detail::box_for_writing(packing), /*allow_short_form=*/true));
    if (!options.comment.empty())
      fmt::format_to(std::back_inserter(buffer), "# packlab: {}\n", detail::single_line(options.comment));
    for (std::size_t k = 0; k < packing.size(); ++k) {
      const Vec3& p = packing.position[k];
      fmt::format_to(std::back_inserter(buffer), "{:.17g} {:.17g} {:.17g} {:.17g}", p.x, p.y, p.z,
                     packing.radius[k]);
      if (with_type) fmt::format_to(std::back_inserter(buffer), " {}", packing.type[k]);
      buffer.push_back('\n');
      if (buffer.size() > (1u << 20)) flush();
    }
    flush();
  });
}

}  // namespace packlab::io
