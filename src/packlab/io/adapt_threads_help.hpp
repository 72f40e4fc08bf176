// The help of the adapt_threads key (dem::EngineConfig::adapt_threads), one text for every
// command that runs the explicit engine (io/options.cpp, io/mechanics_options.cpp).
#pragma once

#include <string>
#include <string_view>

namespace packlab::io {

// `when`: under what the adaptation applies, e.g. "With more than one thread".
inline std::string adapt_threads_help(std::string_view when) {
  return std::string(when) +
         " (threads = 0: every core): start at one thread and use the configured count while probes find it faster "
         "(a busy machine can make threads slower than one, docs/engine.md \"Parallelism\"); false: the configured "
         "count from the first step. The results do not depend on it";
}

}  // namespace packlab::io
