// packlab build opal (issue #7): placeholder registered by the lead; the owner replaces it.
#include "packlab/cli/commands.hpp"

namespace packlab::cli {

void add_build_opal(CLI::App& /*build*/) {}

}  // namespace packlab::cli
