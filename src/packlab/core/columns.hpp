// A table of named columns: the one view of a result's rows that the CSV writers
// (io/table.hpp) and the Python module (NumPy arrays) both read, so that a column is named and
// converted in one place.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace packlab {

struct Column {
  enum class Kind { real, integer, flag };  // flag: 0/1 (NumPy bool); integer: counts, indices (int64)
  std::string name;
  std::vector<double> values;
  Kind kind = Kind::real;
  int digits = 17;  // significant digits of a real value written as text
};

struct Columns {
  std::vector<Column> columns;

  void add(std::string name, std::vector<double> values, Column::Kind kind = Column::Kind::real, int digits = 17) {
    columns.push_back(Column{std::move(name), std::move(values), kind, digits});
  }
  std::size_t rows() const { return columns.empty() ? 0 : columns.front().values.size(); }
};

}  // namespace packlab
