// Option sets: each command declares its options once, as fields bound to the variables they
// set (key, type, unit, allowed range, one line of documentation; the default is the
// variable's value when the set is declared, i.e. its struct member's initializer). The same
// declaration
//   - reads the config file (TOML; unknown keys, wrong types: InputError naming file, key and
//     what is allowed): read_file();
//   - names the command-line flags (cli/options.hpp): `relax.max_steps` is --relax-max-steps;
//   - names the Python keywords (python/src/common.hpp): `relax.max_steps` is relax_max_steps;
//   - writes the report's `parameters` block: json();
//   - writes the reference table of every key (`packlab config-keys`, docs/config-reference.md),
// so no default, unit or range is written twice and the documentation cannot drift from the code.
//
// Keys are dotted paths: "relax.tolerance" is `tolerance` in the table `[relax]`. Every source
// goes through set(), so a value reads the same from a file, a flag or a keyword.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "packlab/core/parameter.hpp"

namespace packlab::io {

class ConfigSchema {
 public:
  // A value as a front end read it, before it is checked against the field's type.
  using Value = std::variant<double, std::int64_t, bool, std::string, std::vector<double>>;
  using Target = std::variant<double*, long*, int*, std::uint64_t*, bool*, std::string*, std::vector<double*>,
                              std::vector<double>*>;

  struct Field {
    std::string key;           // "relax.max_steps"
    std::string type;          // number | integer | boolean | string | numbers
    std::string default_text;  // the value when declared, as the docs print it
    std::string description;   // one line
    std::string unit;          // SI unit as printed ("N/m"), "" if dimensionless
    std::optional<Range> range;
    std::vector<std::string> aliases;  // further snake_case names of its flag and keyword
    bool python = true;                // a keyword of the Python function (else command line and file only)
    bool report = true;                // in json()
    Target target;
    // The value a run saved before this key existed ran with (set_values() gives it to a saved
    // record that lacks the key); null: such a record keeps the current value.
    nlohmann::json value_when_not_saved = nullptr;

    std::string flag() const;                   // "--relax-max-steps"
    std::string keyword() const;                // "relax_max_steps"
    std::vector<std::string> flags() const;     // flag() and those of the aliases
    std::vector<std::string> keywords() const;  // keyword() and the aliases
    nlohmann::json value() const;               // the target's current value
  };

  // `command` as typed ("generate vem"), `summary` one line on what the set configures,
  // `python_function` the function of the Python module taking the same options as keywords.
  explicit ConfigSchema(std::string command, std::string summary = "", std::string python_function = "");

  // Each registers a key bound to `target`; the default shown is target's current value.
  ConfigSchema& number(const std::string& key, double& target, const std::string& description);
  ConfigSchema& integer(const std::string& key, long& target, const std::string& description);
  ConfigSchema& integer(const std::string& key, int& target, const std::string& description);
  ConfigSchema& integer(const std::string& key, std::uint64_t& target, const std::string& description);
  ConfigSchema& boolean(const std::string& key, bool& target, const std::string& description);
  ConfigSchema& text(const std::string& key, std::string& target, const std::string& description);
  // A list of numbers: a TOML array, a comma-separated flag value (1,0.313), a Python sequence.
  ConfigSchema& numbers(const std::string& key, std::vector<double>& target, const std::string& description);
  // A number that sets several variables (e.g. one damping for every material); not reported
  // (the variables it sets are).
  ConfigSchema& number_to_all(const std::string& key, std::vector<double*> targets, const std::string& description);
  // Parameters declared with packlab::Parameter (a law's or a material's), as `section.name`.
  template <class Owner, class Parameters>
  ConfigSchema& parameters(const std::string& section, Owner& owner, const Parameters& list) {
    const std::string prefix = section.empty() ? "" : section + ".";
    for (const Parameter<Owner>& p : list) {
      const std::string key = prefix + std::string(p.name);
      if (p.is_boolean()) {
        boolean(key, owner.*std::get<bool Owner::*>(p.member), std::string(p.doc));
      } else {
        number(key, owner.*std::get<double Owner::*>(p.member), std::string(p.doc));
        range(p.range);
      }
      unit(std::string(p.unit));
    }
    return *this;
  }

  // Modifiers of the field registered last.
  ConfigSchema& unit(std::string unit);
  ConfigSchema& range(const Range& range);
  // A further name: flag --snake-name and Python keyword snake_name (e.g. "max_q" for stop.max_q).
  ConfigSchema& alias(std::string snake_name);
  // A setting of the command's run (output, analysis of its tables): command line and file only.
  ConfigSchema& command_only();
  // A key added after runs were saved with the set: the value those runs ran with, which
  // differs from today's default (a resumed old checkpoint must go on as it started).
  ConfigSchema& when_not_saved(nlohmann::json value);

  // The fields of `other` (bound to its targets) after these.
  ConfigSchema& append(const ConfigSchema& other);

  const std::vector<Field>& fields() const { return fields_; }
  // The field named `name` as a key, flag or keyword (aliases included); null if none.
  const Field* find(std::string_view name) const;
  // Sets the field's target. `source` names the value in messages ("file.toml: relax.max_steps",
  // "--relax-max-steps", "relax_max_steps"); InputError when the type does not fit (an integer
  // where a number is wanted is fine).
  static void set(const Field& field, const Value& value, std::string_view source);
  // The same from text (a command-line value): numbers, integers, true/false (1/0, yes/no).
  static void set_text(const Field& field, const std::string& text, std::string_view source);

  // Throws InputError for a parse error, an unknown key or a value of the wrong type; a bad
  // file changes nothing.
  void read_file(const std::filesystem::path& file) const;
  // InputError "key = value: must be <range>" for the first value outside its declared range.
  void validate() const;

  // The report's `parameters` block: nested objects by section, each value under its key's last
  // name with its unit ("radius_m", "normal_stiffness_N_per_m"); reported fields only.
  nlohmann::json json() const;
  // Every field's current value by key, reported or not: the settings of a run as its
  // checkpoint keeps them. set_values() puts such a record back (through set(), so a value that
  // does not fit its field is an InputError naming `source` and the key); keys it lacks keep
  // their values or take their when_not_saved() value, keys the set lacks are an InputError.
  nlohmann::json values() const;
  void set_values(const nlohmann::json& values, std::string_view source) const;
  // Markdown section: a heading with the command and a table key | type | default | unit |
  // allowed | description.
  std::string markdown() const;
  // One line per Python keyword (name, type, default, unit, range, description) for docstrings.
  std::string python_doc() const;
  const std::string& command() const { return command_; }
  std::vector<std::string> keys() const;
  std::vector<std::string> keywords() const;  // Python keywords, aliases included

 private:
  ConfigSchema& add(Field field);
  Field& last();

  std::string command_, summary_, python_function_;
  std::vector<Field> fields_;
};

// "N/m" -> "N_per_m", "kg/m^3" -> "kg_per_m3": the unit as a suffix of a report name.
std::string unit_suffix(std::string_view unit);

}  // namespace packlab::io
