#include "packlab/core/error.hpp"

#include <fmt/format.h>

namespace packlab {

void fail_input(const std::string& message) { throw InputError(message); }

void require(bool ok, const std::string& key, double value, const std::string& requirement) {
  if (!ok) throw InputError(fmt::format("{} = {:g}: must be {}", key, value, requirement));
}

}  // namespace packlab
