// packlab calibrate compress (issue #7): placeholder registered by the lead; the owner replaces it.
#include "packlab/cli/commands.hpp"

namespace packlab::cli {

void add_calibrate_compress(CLI::App& /*calibrate*/) {}

}  // namespace packlab::cli
