// One error type for bad input: the command line prints its message on one line and exits
// with code 2 (DESIGN.md conventions). Internal bugs stay std::logic_error and crash loudly.
#pragma once

#include <stdexcept>
#include <string>

namespace packlab {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "key = value: must be in range" messages, so every check reads the same.
[[noreturn]] void fail_input(const std::string& message);

// Throws InputError("<key> = <value>: must be <requirement>") unless ok.
void require(bool ok, const std::string& key, double value, const std::string& requirement);

}  // namespace packlab
