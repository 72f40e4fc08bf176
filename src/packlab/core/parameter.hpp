// A parameter declared once: its name, unit, allowed range and one line of documentation,
// bound to the member of the struct that holds it. Validation messages, config keys, command-
// line flags, Python keywords, report blocks and the generated docs all read this declaration,
// so no default, range or unit is written twice (DESIGN.md conventions). The default is the
// member's initializer in its struct.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace packlab {

// An interval of allowed values; open or closed at each end, infinite ends allowed. Finite
// values only unless an end is infinite and closed (`inf` then means "never", e.g. a strength).
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;

  bool contains(double v) const {
    if (std::isnan(v)) return false;
    if (min_open ? !(v > min) : !(v >= min)) return false;
    if (max_open ? !(v < max) : !(v <= max)) return false;
    if (std::isinf(v) && !(v == max && !max_open && std::isinf(max))) return false;
    return true;
  }
  // "> 0 N/m", ">= 0", "in (0, 1]", "<= 2 m", "any finite value", with " (inf: never)" where
  // +inf is allowed.
  std::string text(std::string_view unit = "") const;
};

namespace ranges {
inline constexpr double inf = std::numeric_limits<double>::infinity();
inline constexpr Range any{};
inline constexpr Range positive{0.0, inf, true, true};             // > 0, finite
inline constexpr Range non_negative{0.0, inf, false, true};        // >= 0, finite
inline constexpr Range non_negative_or_inf{0.0, inf, false, false};  // >= 0, inf allowed
inline constexpr Range positive_or_inf{0.0, inf, true, false};     // > 0, inf allowed
inline constexpr Range unit_interval{0.0, 1.0, false, false};      // [0, 1]
}  // namespace ranges

// One parameter of struct Owner. Booleans carry no range.
template <class Owner>
struct Parameter {
  std::string_view name;  // snake_case key: "normal_stiffness"
  std::string_view unit;  // SI unit as printed ("N/m", "Pa", "" for dimensionless)
  std::string_view doc;   // one line: what it is, with the paper's symbol
  std::variant<double Owner::*, bool Owner::*> member;
  Range range = ranges::any;

  bool is_boolean() const { return std::holds_alternative<bool Owner::*>(member); }
  double get(const Owner& o) const {
    return is_boolean() ? static_cast<double>(o.*std::get<bool Owner::*>(member)) : o.*std::get<double Owner::*>(member);
  }
  void set(Owner& o, double v) const {
    if (is_boolean())
      o.*std::get<bool Owner::*>(member) = v != 0.0;
    else
      o.*std::get<double Owner::*>(member) = v;
  }
};

// Throws InputError "<prefix><name> = <value>: must be <range text>" for the first value of
// `owner` outside its range.
void require_in_range(std::string_view prefix, std::string_view name, double value, const Range& range,
                      std::string_view unit);

template <class Owner, class Parameters>
void validate_parameters(const Owner& owner, const Parameters& parameters, std::string_view prefix = "") {
  for (const Parameter<Owner>& p : parameters)
    if (!p.is_boolean()) require_in_range(prefix, p.name, p.get(owner), p.range, p.unit);
}

}  // namespace packlab
