// A Columns table (core/columns.hpp) as a dict of NumPy arrays: reals float64, integers int64,
// flags bool; the same names as the CSV files of the command line.
#pragma once

#include <cstdint>
#include <vector>

#include "common.hpp"
#include "packlab/core/columns.hpp"

namespace packlab::python {

inline py::dict columns_dict(const Columns& table) {
  py::dict d;
  for (const Column& c : table.columns) {
    if (c.kind == Column::Kind::real) {
      d[py::str(c.name)] = to_numpy(std::vector<double>(c.values));
    } else if (c.kind == Column::Kind::integer) {
      d[py::str(c.name)] = to_numpy(std::vector<long>(c.values.begin(), c.values.end()));
    } else {
      std::vector<std::uint8_t> flags;
      for (double v : c.values) flags.push_back(v != 0.0 ? 1 : 0);
      d[py::str(c.name)] = to_numpy_bool(std::move(flags));
    }
  }
  return d;
}

}  // namespace packlab::python
