// The message of the InputError a call throws, for tests that check what it says.
#pragma once

#include <functional>
#include <string>

#include "packlab/core/error.hpp"

namespace packlab::test {

// The message of the InputError that f() throws; "" when it throws none.
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace packlab::test
