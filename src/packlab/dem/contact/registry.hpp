// The registered contact laws: one line each. Everything the engine, the command line, the
// Python module and the docs know about contact laws (names, validation of the material
// properties each reads, the checkpoint tag, the per-law pair loop) comes from this list.
#pragma once

#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "packlab/dem/contact/dlvo.hpp"
#include "packlab/dem/contact/hertz_mindlin.hpp"
#include "packlab/dem/contact/linear.hpp"
#include "packlab/dem/contact/linear_adhesive.hpp"

namespace packlab::dem {

template <class... Laws>
struct LawList {
  static std::vector<std::string> names() { return {std::string(Laws::name)...}; }
  // Calls f(std::type_identity<Law>{}) for the law called `name`; false if there is none.
  template <class F>
  static bool with_law(std::string_view name, F&& f) {
    return ((name == Laws::name ? (f(std::type_identity<Laws>{}), true) : false) || ...);
  }
  // Calls f(std::type_identity<Law>{}) for every law, in list order.
  template <class F>
  static void for_each(F&& f) {
    (f(std::type_identity<Laws>{}), ...);
  }
  template <template <class> class Holder>
  using variant = std::variant<Holder<Laws>...>;
};

using ContactLaws = LawList<LinearContact, HertzMindlin, LinearAdhesive, Dlvo>;

}  // namespace packlab::dem
