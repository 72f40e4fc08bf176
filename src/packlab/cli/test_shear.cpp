// packlab test shear (issue #6): placeholder registered by the lead; the owner replaces it.
#include "packlab/cli/commands.hpp"

namespace packlab::cli {

void add_test_shear(CLI::App& /*test*/) {}

}  // namespace packlab::cli
