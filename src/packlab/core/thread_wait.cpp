#include "packlab/core/thread_wait.hpp"

#include <unistd.h>

#include <cstdlib>

namespace packlab {

void ensure_passive_thread_wait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
  // The same program with the same arguments; if that fails, go on with the default policy.
  execv("/proc/self/exe", argv);
}

}  // namespace packlab
