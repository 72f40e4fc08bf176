#include "packlab/io/config.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

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

std::string unit_suffix(std::string_view unit) {
  std::string out;
  for (const char c : unit) {
    if (c == '/')
      out += "_per_";
    else if (c == '^' || c == ' ')
      continue;
    else
      out += c;
  }
  return out;
}

namespace {

std::string snake_to_flag(std::string name) {
  std::replace(name.begin(), name.end(), '.', '-');
  std::replace(name.begin(), name.end(), '_', '-');
  return "--" + name;
}

std::string key_to_keyword(std::string key) {
  std::replace(key.begin(), key.end(), '.', '_');
  return key;
}

std::string list_text(const std::vector<double>& v) {
  std::string out;
  for (const double x : v) out += (out.empty() ? "" : ", ") + shortest(x);
  return "[" + out + "]";
}

std::string type_text(const ConfigSchema::Value& v) {
  return std::visit(
      Overloaded{[](double x) { return shortest(x); }, [](std::int64_t x) { return fmt::format("{}", x); },
                 [](bool x) { return std::string(x ? "true" : "false"); },
                 [](const std::string& x) { return "\"" + x + "\""; },
                 [](const std::vector<double>& x) { return list_text(x); }},
      v);
}

}  // namespace

std::string ConfigSchema::Field::flag() const { return snake_to_flag(key); }
std::string ConfigSchema::Field::keyword() const { return key_to_keyword(key); }

std::vector<std::string> ConfigSchema::Field::flags() const {
  std::vector<std::string> out{flag()};
  for (const std::string& a : aliases) out.push_back(snake_to_flag(a));
  return out;
}

std::vector<std::string> ConfigSchema::Field::keywords() const {
  std::vector<std::string> out{keyword()};
  out.insert(out.end(), aliases.begin(), aliases.end());
  return out;
}

nlohmann::json ConfigSchema::Field::value() const {
  return std::visit(Overloaded{[](const std::vector<double*>& ts) {
                                 return ts.empty() ? nlohmann::json() : nlohmann::json(*ts.front());
                               },
                               [](auto* t) { return nlohmann::json(*t); }},
                    target);
}

ConfigSchema::ConfigSchema(std::string command, std::string summary, std::string python_function)
    : command_(std::move(command)), summary_(std::move(summary)), python_function_(std::move(python_function)) {}

ConfigSchema& ConfigSchema::add(Field field) {
  fields_.push_back(std::move(field));
  return *this;
}

ConfigSchema::Field& ConfigSchema::last() {
  if (fields_.empty()) throw std::logic_error("ConfigSchema: a modifier before the first field");
  return fields_.back();
}

ConfigSchema& ConfigSchema::number(const std::string& key, double& target, const std::string& description) {
  return add({key, "number", shortest(target), description, "", {}, {}, true, true, &target});
}
ConfigSchema& ConfigSchema::integer(const std::string& key, long& target, const std::string& description) {
  return add({key, "integer", fmt::format("{}", target), description, "", {}, {}, true, true, &target});
}
ConfigSchema& ConfigSchema::integer(const std::string& key, int& target, const std::string& description) {
  return add({key, "integer", fmt::format("{}", target), description, "", {}, {}, true, true, &target});
}
ConfigSchema& ConfigSchema::integer(const std::string& key, std::uint64_t& target, const std::string& description) {
  return add({key, "integer", fmt::format("{}", target), description, "", {}, {}, true, true, &target});
}
ConfigSchema& ConfigSchema::boolean(const std::string& key, bool& target, const std::string& description) {
  return add({key, "boolean", target ? "true" : "false", description, "", {}, {}, true, true, &target});
}
ConfigSchema& ConfigSchema::text(const std::string& key, std::string& target, const std::string& description) {
  return add({key, "string", "\"" + target + "\"", description, "", {}, {}, true, true, &target});
}
ConfigSchema& ConfigSchema::numbers(const std::string& key, std::vector<double>& target,
                                    const std::string& description) {
  return add({key, "numbers", list_text(target), description, "", {}, {}, true, true, &target});
}
ConfigSchema& ConfigSchema::number_to_all(const std::string& key, std::vector<double*> targets,
                                          const std::string& description) {
  const std::string def = targets.empty() ? "" : shortest(*targets.front());
  return add({key, "number", def, description, "", {}, {}, true, false, std::move(targets)});
}

ConfigSchema& ConfigSchema::unit(std::string unit) {
  last().unit = std::move(unit);
  return *this;
}
ConfigSchema& ConfigSchema::range(const Range& range) {
  last().range = range;
  return *this;
}
ConfigSchema& ConfigSchema::alias(std::string snake_name) {
  last().aliases.push_back(std::move(snake_name));
  return *this;
}
ConfigSchema& ConfigSchema::command_only() {
  last().python = false;
  return *this;
}
namespace {

// A saved record's value (JSON) as the value a front end reads; InputError "WHERE = value: ..."
// when it is no value an option takes.
ConfigSchema::Value value_of_json(const nlohmann::json& value, std::string_view where) {
  if (value.is_boolean()) return value.get<bool>();
  if (value.is_number_unsigned() &&
      value.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
    fail_input(fmt::format("{} = {}: out of range", where, value.dump()));
  if (value.is_number_integer()) return value.get<std::int64_t>();
  if (value.is_number_float()) return value.get<double>();
  if (value.is_string()) return value.get<std::string>();
  if (value.is_array() && std::all_of(value.begin(), value.end(), [](const auto& x) { return x.is_number(); }))
    return value.get<std::vector<double>>();
  fail_input(fmt::format("{} = {}: not a value this option takes", where, value.dump()));
}

// ConfigSchema::set() on a copy of the field bound to scratch variables: the same checks
// (type, integer range) without applying the value.
void check_value(const ConfigSchema::Field& field, const ConfigSchema::Value& value, std::string_view source) {
  using Target = ConfigSchema::Target;
  double d = 0.0;
  long l = 0;
  int i = 0;
  std::uint64_t u = 0;
  bool b = false;
  std::string text;
  std::vector<double> list;
  ConfigSchema::Field scratch = field;
  scratch.target = std::visit(
      Overloaded{[&](double*) -> Target { return &d; }, [&](const std::vector<double*>&) -> Target { return &d; },
                 [&](long*) -> Target { return &l; }, [&](int*) -> Target { return &i; },
                 [&](std::uint64_t*) -> Target { return &u; }, [&](bool*) -> Target { return &b; },
                 [&](std::string*) -> Target { return &text; }, [&](std::vector<double>*) -> Target { return &list; }},
      field.target);
  ConfigSchema::set(scratch, value, source);
}

}  // namespace

ConfigSchema& ConfigSchema::when_not_saved(nlohmann::json value) {
  // A value of the wrong type would surface only when an old checkpoint is resumed, as an
  // error blaming the saved settings: refuse it where it is declared, by the checks a saved
  // record's value goes through (set_values).
  try {
    check_value(last(), value_of_json(value, last().key), last().key);
  } catch (const InputError& e) {
    throw std::logic_error(fmt::format("when_not_saved({}) does not fit {} field {}: {}", value.dump(), last().type,
                                       last().key, e.what()));
  }
  last().value_when_not_saved = std::move(value);
  return *this;
}
ConfigSchema& ConfigSchema::append(const ConfigSchema& other) {
  fields_.insert(fields_.end(), other.fields_.begin(), other.fields_.end());
  return *this;
}

std::vector<std::string> ConfigSchema::keys() const {
  std::vector<std::string> out;
  for (const Field& f : fields_) out.push_back(f.key);
  return out;
}

std::vector<std::string> ConfigSchema::keywords() const {
  std::vector<std::string> out;
  for (const Field& f : fields_)
    if (f.python)
      for (std::string& k : f.keywords()) out.push_back(std::move(k));
  return out;
}

const ConfigSchema::Field* ConfigSchema::find(std::string_view name) const {
  for (const Field& f : fields_) {
    if (f.key == name) return &f;
    for (const std::string& n : f.flags())
      if (n == name) return &f;
    for (const std::string& n : f.keywords())
      if (n == name) return &f;
  }
  return nullptr;
}

void ConfigSchema::set(const Field& field, const Value& value, std::string_view source) {
  const auto wrong = [&](const char* what) {
    fail_input(fmt::format("{} = {}: must be {}", source, type_text(value), what));
  };
  std::visit(Overloaded{
                 [&](double* t) {
                   if (const auto* i = std::get_if<std::int64_t>(&value))
                     *t = static_cast<double>(*i);
                   else if (const auto* d = std::get_if<double>(&value))
                     *t = *d;
                   else
                     wrong("a number");
                 },
                 [&](const std::vector<double*>& ts) {
                   double v = 0.0;
                   if (const auto* i = std::get_if<std::int64_t>(&value))
                     v = static_cast<double>(*i);
                   else if (const auto* d = std::get_if<double>(&value))
                     v = *d;
                   else
                     wrong("a number");
                   for (double* t : ts) *t = v;
                 },
                 [&](bool* t) {
                   if (const auto* b = std::get_if<bool>(&value))
                     *t = *b;
                   else
                     wrong("true or false");
                 },
                 [&](std::string* t) {
                   if (const auto* s = std::get_if<std::string>(&value))
                     *t = *s;
                   else
                     wrong("a string in quotes");
                 },
                 [&](std::vector<double>* t) {
                   if (const auto* l = std::get_if<std::vector<double>>(&value))
                     *t = *l;
                   else
                     wrong("a list of numbers");
                 },
                 [&](auto* t) {  // the integer types
                   using T = std::remove_pointer_t<decltype(t)>;
                   const auto* i = std::get_if<std::int64_t>(&value);
                   if (!i) wrong("an integer");
                   if (*i < static_cast<std::int64_t>(std::numeric_limits<T>::min()) ||
                       static_cast<long double>(*i) > static_cast<long double>(std::numeric_limits<T>::max()))
                     fail_input(fmt::format("{} = {}: out of range", source, *i));
                   *t = static_cast<T>(*i);
                 },
             },
             field.target);
}

void ConfigSchema::set_text(const Field& field, const std::string& text, std::string_view source) {
  const auto fail = [&](const char* what) { fail_input(fmt::format("{} = {}: must be {}", source, text, what)); };
  if (field.type == "string") return set(field, text, source);
  if (field.type == "numbers") {
    std::vector<double> list;
    std::size_t begin = 0;
    while (begin <= text.size() && !text.empty()) {
      const std::size_t comma = std::min(text.find(',', begin), text.size());
      const std::string item = text.substr(begin, comma - begin);
      std::size_t n = 0;
      try {
        list.push_back(std::stod(item, &n));
      } catch (const std::exception&) {
        n = std::string::npos;
      }
      if (n != item.size()) fail("a comma-separated list of numbers");
      begin = comma + 1;
    }
    return set(field, list, source);
  }
  if (field.type == "boolean") {
    if (text == "true" || text == "1" || text == "yes" || text == "on") return set(field, true, source);
    if (text == "false" || text == "0" || text == "no" || text == "off") return set(field, false, source);
    fail("true or false");
  }
  std::size_t used = 0;
  if (field.type == "integer") {
    std::int64_t v = 0;
    try {
      v = std::stoll(text, &used);
    } catch (const std::out_of_range&) {
      fail_input(fmt::format("{} = {}: out of range", source, text));
    } catch (const std::exception&) {
      fail("an integer");
    }
    if (used != text.size()) fail("an integer");
    return set(field, v, source);
  }
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    fail("a number");
  }
  if (used != text.size()) fail("a number");
  set(field, v, source);
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
      const auto it = std::find_if(fields_.begin(), fields_.end(), [&](const Field& f) { return f.key == full; });
      if (it == fields_.end()) {
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
      Value value;
      if (node.is_boolean()) {
        value = *node.template value<bool>();
      } else if (node.is_integer()) {
        value = *node.template value<std::int64_t>();
      } else if (node.is_floating_point()) {
        value = *node.template value<double>();
      } else if (node.is_string()) {
        value = *node.template value<std::string>();
      } else if (node.is_array() && it->type == "numbers") {
        std::vector<double> list;
        for (const toml::node& item : *node.as_array()) {
          const auto v = item.template value<double>();
          if (!v || item.is_boolean()) bad(file, full, "must be a list of numbers");
          list.push_back(*v);
        }
        value = std::move(list);
      } else {
        const char* what = it->type == "number"    ? "must be a number"
                           : it->type == "integer" ? "must be an integer"
                           : it->type == "boolean" ? "must be true or false"
                           : it->type == "numbers" ? "must be a list of numbers"
                                                   : "must be a string in quotes";
        bad(file, full, what);
      }
      if (apply)
        set(*it, value, file + ": " + full);
      else
        check_value(*it, value, file + ": " + full);
    }
  };
  // Two passes: check everything first, so a bad file changes nothing.
  walk(walk, root, "", false);
  walk(walk, root, "", true);
}

void ConfigSchema::validate() const {
  for (const Field& f : fields_) {
    if (!f.range) continue;
    const nlohmann::json v = f.value();
    if (v.is_number()) require_in_range("", f.key, v.get<double>(), *f.range, f.unit);
    if (v.is_array())  // a list of numbers: each in the range
      for (const nlohmann::json& e : v)
        if (e.is_number()) require_in_range("", f.key, e.get<double>(), *f.range, f.unit);
  }
}

nlohmann::json ConfigSchema::json() const {
  nlohmann::json out = nlohmann::json::object();
  for (const Field& f : fields_) {
    if (!f.report) continue;
    nlohmann::json* node = &out;
    std::string rest = f.key;
    for (auto dot = rest.find('.'); dot != std::string::npos; dot = rest.find('.')) {
      node = &(*node)[rest.substr(0, dot)];
      rest = rest.substr(dot + 1);
    }
    (*node)[f.unit.empty() ? rest : rest + "_" + unit_suffix(f.unit)] = f.value();
  }
  return out;
}

nlohmann::json ConfigSchema::values() const {
  nlohmann::json out = nlohmann::json::object();
  for (const Field& f : fields_) out[f.key] = f.value();
  return out;
}

void ConfigSchema::set_values(const nlohmann::json& saved, std::string_view source) const {
  if (!saved.is_object()) fail_input(fmt::format("{}: the settings are not a table of keys", source));
  nlohmann::json values = saved;
  for (const Field& f : fields_) {
    if (f.value_when_not_saved.is_null()) continue;
    // Saved under the key or under one of its other names: the record has it.
    bool saved_here = false;
    for (const auto& item : saved.items()) saved_here = saved_here || find(item.key()) == &f;
    if (!saved_here) values[f.key] = f.value_when_not_saved;
  }
  for (const auto& [key, value] : values.items()) {
    const Field* field = find(key);
    const std::string where = fmt::format("{}: {}", source, key);
    if (field == nullptr) fail_input(fmt::format("{}: not an option of packlab {}", where, command_));
    set(*field, value_of_json(value, where), where);
  }
}

std::string ConfigSchema::markdown() const {
  std::string out = fmt::format("## `packlab {}`\n\n", command_);
  if (!summary_.empty()) out += summary_ + "\n\n";
  if (!python_function_.empty()) {
    // One function, or several classes whose keywords together are the set ("A, B").
    std::string python;
    for (std::size_t begin = 0; begin <= python_function_.size();) {
      const std::size_t comma = std::min(python_function_.find(", ", begin), python_function_.size());
      python +=
          fmt::format("{}`packlab.{}(...)`", python.empty() ? "" : ", ", python_function_.substr(begin, comma - begin));
      begin = comma + 2;
    }
    out += fmt::format(
        "Flags: `--` and the key with `-` for `.` and `_`; Python: {} with the key "
        "with `_` for `.` as keyword (settings marked *command line* excepted).\n\n",
        python);
  }
  out += "| key | type | default | unit | allowed | description |\n|---|---|---|---|---|---|\n";
  for (const Field& f : fields_) {
    std::string description = f.description;
    if (!f.aliases.empty()) {
      std::string names;
      for (const std::string& a : f.aliases) names += (names.empty() ? "" : ", ") + snake_to_flag(a);
      description += " (also " + names + ")";
    }
    if (!python_function_.empty() && !f.python) description += " *command line*";
    std::replace(description.begin(), description.end(), '|', '/');
    out += fmt::format("| `{}` | {} | `{}` | {} | {} | {} |\n", f.key, f.type, f.default_text, f.unit,
                       f.range ? f.range->text() : "", description);
  }
  return out + "\n";
}

std::string ConfigSchema::python_doc() const {
  std::string out;
  for (const Field& f : fields_) {
    if (!f.python) continue;
    std::string names;
    for (const std::string& k : f.keywords()) names += (names.empty() ? "" : " or ") + k;
    out += fmt::format("  {} ({}, default {}{}{}): {}\n", names, f.type, f.default_text,
                       f.unit.empty() ? "" : " " + f.unit, f.range ? ", " + f.range->text(f.unit) : "", f.description);
  }
  return out;
}

}  // namespace packlab::io
