#include "packlab/io/table.hpp"

#include <fmt/format.h>

#include <iterator>

namespace packlab::io {

std::string csv_header(const Columns& table, std::string_view label_name) {
  std::string out(label_name);
  for (const Column& c : table.columns) {
    if (!out.empty()) out += ',';
    out += c.name;
  }
  out += '\n';
  return out;
}

void append_csv_rows(std::string& csv, const Columns& table, std::string_view label) {
  auto out = std::back_inserter(csv);
  for (std::size_t row = 0; row < table.rows(); ++row) {
    bool first = label.empty();
    if (!first) fmt::format_to(out, "{}", label);
    for (const Column& c : table.columns) {
      if (!first) csv += ',';
      first = false;
      const double v = c.values[row];
      if (c.kind == Column::Kind::real)
        fmt::format_to(out, "{:.{}g}", v, c.digits);
      else
        fmt::format_to(out, "{}", static_cast<long long>(v));
    }
    csv += '\n';
  }
}

std::string to_csv(const Columns& table) {
  std::string csv = csv_header(table);
  append_csv_rows(csv, table);
  return csv;
}

}  // namespace packlab::io
