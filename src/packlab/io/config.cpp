#include "packlab/io/config.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <toml++/toml.h>

#include "packlab/core/error.hpp"

namespace packlab::io {

namespace {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};

std::string shortest(double v) { return fmt::format("{}", v); }

[[noreturn]] void bad(const std::string& file, const std::string& key, const std::string& why) {
  fail_input(fmt::format("{}: {} = ...: {}", file, key, why));
}

// The names directly below `prefix` (keys and sub-tables), for the "known:" list.
std::vector<std::string> names_below(const std::vector<std::string>& keys, const std::string& prefix) {
  std::vector<std::string> names;
  for (const std::string& k : keys) {
    if (k.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = k.substr(prefix.size());
    const auto dot = rest.find('.');
    const std::string name = dot == std::string::npos ? rest : "[" + prefix + rest.substr(0, dot) + "]";
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  return names;
}

}  // namespace

ConfigSchema::ConfigSchema(std::string command, std::string summary)
    : command_(std::move(command)), summary_(std::move(summary)) {}

ConfigSchema& ConfigSchema::add(Key key) {
  keys_.push_back(std::move(key));
  return *this;
}

ConfigSchema& ConfigSchema::number(const std::string& key, double& target, const std::string& description) {
  return add({key, "number", shortest(target), description, &target});
}
ConfigSchema& ConfigSchema::integer(const std::string& key, long& target, const std::string& description) {
  return add({key, "integer", fmt::format("{}", target), description, &target});
}
ConfigSchema& ConfigSchema::integer(const std::string& key, int& target, const std::string& description) {
  return add({key, "integer", fmt::format("{}", target), description, &target});
}
ConfigSchema& ConfigSchema::integer(const std::string& key, std::uint64_t& target, const std::string& description) {
  return add({key, "integer", fmt::format("{}", target), description, &target});
}
ConfigSchema& ConfigSchema::boolean(const std::string& key, bool& target, const std::string& description) {
  return add({key, "boolean", target ? "true" : "false", description, &target});
}
ConfigSchema& ConfigSchema::text(const std::string& key, std::string& target, const std::string& description) {
  return add({key, "string", "\"" + target + "\"", description, &target});
}
ConfigSchema& ConfigSchema::number_to_all(const std::string& key, std::vector<double*> targets,
                                          const std::string& description) {
  const std::string def = targets.empty() ? "" : shortest(*targets.front());
  return add({key, "number", def, description, std::move(targets)});
}

std::vector<std::string> ConfigSchema::keys() const {
  std::vector<std::string> out;
  for (const Key& k : keys_) out.push_back(k.key);
  return out;
}

void ConfigSchema::read_file(const std::filesystem::path& path) const {
  const std::string file = path.string();
  if (!std::filesystem::is_regular_file(path)) fail_input(fmt::format("--config = {}: no such file", file));
  toml::table root;
  try {
    root = toml::parse_file(file);
  } catch (const toml::parse_error& e) {
    fail_input(fmt::format("{}:{}: {}", file, e.source().begin.line, e.description()));
  }
  const std::vector<std::string> all = keys();
  // Walks the tables; every leaf must be a registered key of the right type.
  auto walk = [&](auto&& self, const toml::table& table, const std::string& prefix, bool apply) -> void {
    for (auto&& [k, node] : table) {
      const std::string full = prefix + std::string(k.str());
      const auto it = std::find_if(keys_.begin(), keys_.end(), [&](const Key& key) { return key.key == full; });
      if (it == keys_.end()) {
        const bool is_section = std::any_of(all.begin(), all.end(), [&](const std::string& key) {
          return key.compare(0, full.size() + 1, full + ".") == 0;
        });
        if (is_section) {
          if (!node.is_table()) bad(file, full, fmt::format("must be a table [{}]", full));
          self(self, *node.as_table(), full + ".", apply);
          continue;
        }
        std::string known;
        for (const std::string& name : names_below(all, prefix)) known += (known.empty() ? "" : ", ") + name;
        bad(file, full, "unknown key (known: " + known + ")");
      }
      const auto number = [&] {
        const auto v = node.template value<double>();
        if (!v || node.is_boolean()) bad(file, full, "must be a number");
        return *v;
      };
      std::visit(Overloaded{
                     [&](double* t) {
                       const double v = number();
                       if (apply) *t = v;
                     },
                     [&](const std::vector<double*>& ts) {
                       const double v = number();
                       if (apply)
                         for (double* t : ts) *t = v;
                     },
                     [&](bool* t) {
                       if (!node.is_boolean()) bad(file, full, "must be true or false");
                       if (apply) *t = *node.template value<bool>();
                     },
                     [&](std::string* t) {
                       if (!node.is_string()) bad(file, full, "must be a string in quotes");
                       if (apply) *t = *node.template value<std::string>();
                     },
                     [&](auto* t) {  // the integer types
                       using T = std::remove_pointer_t<decltype(t)>;
                       if (!node.is_integer()) bad(file, full, "must be an integer");
                       const std::int64_t v = *node.template value<std::int64_t>();
                       if (v < static_cast<std::int64_t>(std::numeric_limits<T>::min()) ||
                           static_cast<long double>(v) > static_cast<long double>(std::numeric_limits<T>::max()))
                         bad(file, full, fmt::format("{} is out of range", v));
                       if (apply) *t = static_cast<T>(v);
                     },
                 },
                 it->target);
    }
  };
  // Two passes: check everything first, so a bad file changes nothing.
  walk(walk, root, "", false);
  walk(walk, root, "", true);
}

std::string ConfigSchema::markdown() const {
  std::string out = fmt::format("## `packlab {}`\n\n", command_);
  if (!summary_.empty()) out += summary_ + "\n\n";
  out += "| key | type | default | description |\n|---|---|---|---|\n";
  for (const Key& k : keys_) {
    std::string description = k.description;
    std::replace(description.begin(), description.end(), '|', '/');
    out += fmt::format("| `{}` | {} | `{}` | {} |\n", k.key, k.type, k.default_text, description);
  }
  return out + "\n";
}

}  // namespace packlab::io
