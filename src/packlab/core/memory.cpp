#include "packlab/core/memory.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include "packlab/core/error.hpp"

namespace packlab {

double physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page_size <= 0) return 0.0;
  return static_cast<double>(pages) * static_cast<double>(page_size);
}

void require_memory(std::string_view key, double value, double items, double bytes_per_item) {
  const double available = physical_memory_bytes();
  const double needed = items * bytes_per_item;
  if (available > 0.0 && needed > available)
    fail_input(
        fmt::format("{} = {:g}: about {:.3g} particles need {:.3g} GB ({:g} bytes each), more than the {:.3g} GB "
                    "of this machine",
                    key, value, items, needed * 1e-9, bytes_per_item, available * 1e-9));
}

}  // namespace packlab
