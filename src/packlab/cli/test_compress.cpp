// packlab test compress (issue #7): placeholder registered by the lead; the owner replaces it.
#include "packlab/cli/commands.hpp"

namespace packlab::cli {

void add_test_compress(CLI::App& /*test*/) {}

}  // namespace packlab::cli
