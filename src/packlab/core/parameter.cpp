#include "packlab/core/parameter.hpp"

#include <fmt/format.h>

#include "packlab/core/error.hpp"

namespace packlab {

std::string Range::text(std::string_view unit) const {
  const std::string u = unit.empty() ? std::string() : fmt::format(" {}", unit);
  const bool low = std::isfinite(min), high = std::isfinite(max);
  std::string out;
  if (low && high)
    out = fmt::format("in {}{:g}, {:g}{}{}", min_open ? "(" : "[", min, max, max_open ? ")" : "]", u);
  else if (low)
    out = fmt::format("{} {:g}{}", min_open ? ">" : ">=", min, u);
  else if (high)
    out = fmt::format("{} {:g}{}", max_open ? "<" : "<=", max, u);
  else
    out = fmt::format("a finite number{}", u);
  if (std::isinf(max) && !max_open) out = fmt::format("{} (inf: never)", out);
  return out;
}

void require_in_range(std::string_view prefix, std::string_view name, double value, const Range& range,
                      std::string_view unit) {
  if (!range.contains(value))
    fail_input(fmt::format("{}{} = {:g}: must be {}", prefix, name, value, range.text(unit)));
}

}  // namespace packlab
