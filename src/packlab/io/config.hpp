// Config files (TOML) as a schema: each command declares its keys once, with the variable
// each key sets, its type, default and description. The same declaration reads the file
// (unknown keys, wrong types: InputError naming file, key and what is allowed) and writes the
// reference table of every key (`packlab config-keys`, docs/config-reference.md), so the
// documentation cannot drift from the code.
//
// Keys are dotted paths: "relax.tolerance" is `tolerance` in the table `[relax]`.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

namespace packlab::io {

class ConfigSchema {
 public:
  // `command` as typed ("generate vem"), `summary` one line on what the file configures.
  explicit ConfigSchema(std::string command, std::string summary = "");

  // Each registers a key bound to `target`; the default shown is target's current value.
  ConfigSchema& number(const std::string& key, double& target, const std::string& description);
  ConfigSchema& integer(const std::string& key, long& target, const std::string& description);
  ConfigSchema& integer(const std::string& key, int& target, const std::string& description);
  ConfigSchema& integer(const std::string& key, std::uint64_t& target, const std::string& description);
  ConfigSchema& boolean(const std::string& key, bool& target, const std::string& description);
  ConfigSchema& text(const std::string& key, std::string& target, const std::string& description);
  // A number that sets several variables (e.g. one damping for every material).
  ConfigSchema& number_to_all(const std::string& key, std::vector<double*> targets, const std::string& description);

  // Throws InputError for a parse error, an unknown key or a value of the wrong type.
  void read_file(const std::filesystem::path& file) const;

  // Markdown section: a heading with the command and a table key | type | default | description.
  std::string markdown() const;
  const std::string& command() const { return command_; }
  std::vector<std::string> keys() const;

 private:
  using Target = std::variant<double*, long*, int*, std::uint64_t*, bool*, std::string*, std::vector<double*>>;
  struct Key {
    std::string key, type, default_text, description;
    Target target;
  };
  ConfigSchema& add(Key key);

  std::string command_, summary_;
  std::vector<Key> keys_;
};

}  // namespace packlab::io
