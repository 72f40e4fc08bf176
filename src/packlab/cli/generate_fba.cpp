// packlab generate fba (issue #7): placeholder registered by the lead; the owner replaces it.
#include "packlab/cli/commands.hpp"

namespace packlab::cli {

void add_generate_fba(CLI::App& /*generate*/) {}

}  // namespace packlab::cli
