// The command-line flags of an option set (io/config.hpp): one flag per field, named after its
// key (`relax.max_steps`: --relax-max-steps, plus one per alias), with the field's default,
// unit and description in --help. Flags are read as text and applied after the config file,
// so every command has the same precedence: default < config file < flag.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "packlab/cli/checkpoint.hpp"
#include "packlab/core/error.hpp"
#include "packlab/io/config.hpp"

namespace packlab::cli {

class OptionFlags {
 public:
  // Adds --config FILE (unless `config_file` is false) and the flags of `schema` to `cmd`; the
  // schema's targets must outlive the parse.
  OptionFlags(CLI::App* cmd, io::ConfigSchema schema, bool config_file = true) : schema_(std::move(schema)) {
    if (config_file) cmd->add_option("--config", config_, "TOML file with any of the options; flags override them");
    values_.resize(schema_.fields().size());
    lists_.resize(schema_.fields().size());
    switches_ = std::make_unique<bool[]>(schema_.fields().size());
    for (std::size_t i = 0; i < schema_.fields().size(); ++i) {
      const io::ConfigSchema::Field& f = schema_.fields()[i];
      std::string names;
      for (const std::string& n : f.flags()) names += (names.empty() ? "" : ",") + n;
      std::string help = f.description;
      if (f.range)
        help += "; " + f.range->text(f.unit);
      else if (!f.unit.empty())
        help += " [" + f.unit + "]";
      if (f.type == "boolean") {  // --name sets it, --name=false clears it
        options_.push_back(cmd->add_flag(names, switches_[i], help + " (default " + f.default_text + ")"));
        continue;
      }
      if (f.type == "numbers") {  // 1,0.5 or 1 0.5
        options_.push_back(
            cmd->add_option(names, lists_[i], help)->delimiter(',')->type_name("LIST")->default_str(f.default_text));
        continue;
      }
      CLI::Option* o = cmd->add_option(names, values_[i], help);
      o->type_name(f.type == "number" ? "FLOAT" : f.type == "integer" ? "INT" : "TEXT");
      o->default_str(f.type == "string" ? f.default_text.substr(1, f.default_text.size() - 2) : f.default_text);
      options_.push_back(o);
    }
  }

  // Reads the config file (if one was given), then the flags: default < file < flag.
  void load() const {
    if (!config_.empty()) schema_.read_file(config_);
    apply();
  }
  const std::string& config_file() const { return config_; }

  // Writes the flags given on the command line into the schema's targets.
  void apply() const {
    for (std::size_t i = 0; i < options_.size(); ++i)
      if (options_[i]->count() > 0) {
        const io::ConfigSchema::Field& f = schema_.fields()[i];
        if (f.type == "boolean") {
          io::ConfigSchema::set(f, switches_[i], f.flag());
        } else if (f.type == "numbers") {
          std::string text;
          for (const std::string& item : lists_[i]) text += (text.empty() ? "" : ",") + item;
          io::ConfigSchema::set_text(f, text, f.flag());
        } else {
          io::ConfigSchema::set_text(f, values_[i], f.flag());
        }
      }
  }
  // The first flag of the set that was given, or "" (e.g. to refuse it with --resume).
  std::string first_given(const std::vector<std::string>& except = {}) const {
    for (std::size_t i = 0; i < options_.size(); ++i) {
      if (options_[i]->count() == 0) continue;
      const std::string name = schema_.fields()[i].flag();
      bool skip = false;
      for (const std::string& e : except) skip = skip || schema_.find(e) == &schema_.fields()[i];
      if (!skip) return name;
    }
    return "";
  }
  const io::ConfigSchema& schema() const { return schema_; }

 private:
  io::ConfigSchema schema_;
  std::string config_;                           // --config
  std::vector<std::string> values_;              // the text of each option
  std::vector<std::vector<std::string>> lists_;  // the items of each list option
  std::unique_ptr<bool[]> switches_;             // the boolean fields' flags
  std::vector<CLI::Option*> options_;
};

// A command whose options are one option set: the struct the set binds, the flags with
// --config, and the files and switches every such command has.
template <class Settings>
struct OptionCommand {
  Settings settings;
  std::string in, out;  // the input file (if the command takes one) and --out
  bool quiet = false, no_plots = false;
  std::unique_ptr<OptionFlags> flags;
  // Resumable commands (CommandParts::resumable): --resume DIR. When given, the settings and
  // `in` are those saved in DIR/checkpoint.bin, `out` is DIR and `resumed` holds the method's
  // saved state (cli/checkpoint.hpp).
  std::string resume;
  std::optional<SavedRun> resumed;
};

// What a command adds around its option set, as the help texts of its arguments.
struct CommandParts {
  const char* input = nullptr;     // the positional input file; null: none
  const char* output = nullptr;    // --out (required)
  bool output_positional = false;  // OUT after IN instead of --out
  bool plots = false;              // --no-plots
  bool validate = true;            // check every option against its range before running
  bool resumable = false;          // --resume DIR (cli/checkpoint.hpp); then input and output are optional
                                   // (an output file, output_positional, is then the command's to restore)
};

// --resume DIR of a resumable command: refuses --config, every flag of the set but --threads
// and --adapt-threads, an input file and an --out other than DIR; puts the saved settings into
// the set's targets, then those two flags. Returns the saved run.
SavedRun resume_saved_run(const OptionFlags& flags, const std::string& dir, const std::string& in,
                          const std::string& out);

// Adds subcommand `name` of `parent`: input, the option set `declare(settings)` with --config,
// the output, --no-plots, --quiet. When the command runs, the file and then the flags are read
// (default < file < flag), the ranges checked, and `run(command)` called. Returns the
// subcommand (for further flags, whose storage the caller keeps).
template <class Settings, class Run>
CLI::App* add_option_command(CLI::App& parent, const std::string& name, const std::string& summary,
                             io::ConfigSchema (*declare)(Settings&), const CommandParts& parts, Run run) {
  auto command = std::make_shared<OptionCommand<Settings>>();
  CLI::App* cmd = parent.add_subcommand(name, summary);
  const bool resumable = parts.resumable;
  if (parts.input != nullptr) {
    CLI::Option* in = cmd->add_option("in", command->in, parts.input);
    if (!resumable) in->required();
  }
  if (parts.output != nullptr && parts.output_positional) {
    CLI::Option* out = cmd->add_option("out", command->out, parts.output);
    if (!resumable) out->required();
  }
  command->flags = std::make_unique<OptionFlags>(cmd, declare(command->settings));
  if (parts.output != nullptr && !parts.output_positional) {
    CLI::Option* out = cmd->add_option("--out", command->out, parts.output);
    if (!resumable) out->required();
  }
  if (resumable)
    cmd->add_option("--resume", command->resume,
                    "Continue the run whose checkpoint is in this folder, with its saved settings (--threads may "
                    "change; the DEM engine's result does not depend on it, the static solver's with CHOLMOD does "
                    "in its last digits)");
  if (parts.plots) cmd->add_flag("--no-plots", command->no_plots, "Do not make PNG plots");
  cmd->add_flag("--quiet", command->quiet, "No progress output");
  const bool validate = parts.validate, takes_input = parts.input != nullptr;
  const bool out_file = parts.output_positional;
  cmd->callback([command, run, validate, resumable, takes_input, out_file] {
    if (!command->resume.empty()) {
      // An output file (not a folder) is the saved run's: the command reads it from its state.
      if (out_file && !command->out.empty())
        fail_input("the output file cannot be combined with --resume: the run writes the file it was started with");
      command->resumed.emplace(resume_saved_run(*command->flags, command->resume, command->in, command->out));
      command->in = command->resumed->input;
      if (!out_file) command->out = command->resume;
    } else {
      if (resumable && takes_input && command->in.empty()) fail_input("the input file: required, or --resume DIR");
      if (resumable && command->out.empty())
        fail_input(out_file ? "the output file: required, or --resume DIR"
                            : "--out: required (the output folder), or --resume DIR");
      command->flags->load();
    }
    if (validate) command->flags->schema().validate();
    run(*command);
  });
  return cmd;
}

// The reference table of an option set (`packlab config-keys`, docs/config-reference.md).
template <class Settings>
std::string option_reference(io::ConfigSchema (*declare)(Settings&)) {
  Settings defaults;
  return declare(defaults).markdown();
}

}  // namespace packlab::cli
