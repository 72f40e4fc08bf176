// Building a result's Columns from its rows (one struct per sample, curve point, cycle): a
// column per field, named once.
#pragma once

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "packlab/core/columns.hpp"

namespace packlab::mechanics {

// Appends the column `name` holding value(row) of every row.
template <typename Row, typename Value>
void add_row_column(Columns& table, std::string name, const std::vector<Row>& rows, Value value,
                    Column::Kind kind = Column::Kind::real, int digits = 17) {
  std::vector<double> values;
  values.reserve(rows.size());
  for (const Row& row : rows) values.push_back(static_cast<double>(value(row)));
  table.add(std::move(name), std::move(values), kind, digits);
}

// Appends a real column per (name, field) pair, in order.
template <typename Row>
void add_real_row_columns(Columns& table, const std::vector<Row>& rows,
                          std::initializer_list<std::pair<const char*, double Row::*>> fields, int digits = 17) {
  for (const auto& [name, field] : fields)
    add_row_column(
        table, name, rows, [field](const Row& row) { return row.*field; }, Column::Kind::real, digits);
}

}  // namespace packlab::mechanics
