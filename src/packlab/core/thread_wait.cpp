#include "packlab/core/thread_wait.hpp"

#include <omp.h>
#include <unistd.h>

#include <cstdlib>

namespace packlab {

void fixed_thread_teams() { omp_set_dynamic(0); }

void ensure_passive_thread_wait(char** argv) {
  fixed_thread_teams();
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
  // The same program with the same arguments; if that fails, go on with the default policy.
  execv("/proc/self/exe", argv);
}

}  // namespace packlab
