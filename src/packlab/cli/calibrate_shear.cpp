// packlab calibrate shear (issue #6): placeholder registered by the lead; the owner replaces it.
#include "packlab/cli/commands.hpp"

namespace packlab::cli {

void add_calibrate_shear(CLI::App& /*calibrate*/) {}

}  // namespace packlab::cli
