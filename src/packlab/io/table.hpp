// CSV text of a Columns table (core/columns.hpp): a header line of the column names, then one
// line per row; reals with each column's significant digits, integers and flags without a
// decimal point. An optional first column holds a text label (e.g. the orientation).
#pragma once

#include <string>
#include <string_view>

#include "packlab/core/columns.hpp"

namespace packlab::io {

// "name1,name2,...\n", after `label_name` when it is not empty.
std::string csv_header(const Columns& table, std::string_view label_name = {});
// Appends the rows, each after `label` when `label_name` was given to csv_header.
void append_csv_rows(std::string& csv, const Columns& table, std::string_view label = {});
// Header and rows.
std::string to_csv(const Columns& table);

}  // namespace packlab::io
