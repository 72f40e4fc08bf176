// packlab study SPEC.toml --out DIR [--workers N] [--scheduler tcp://HOST:PORT]
// A study orchestrates processes (a local pool or a Dask cluster, which is Python): this
// command runs the Python runner `python3 -m packlab.studies` in its place (exec), found with
// the same rules as the plots (io/plot.hpp: PACKLAB_PYTHON, PACKLAB_PYTHONPATH, the installed
// or the source tree's package), and tells it this binary's path to run the tasks with.
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "packlab/cli/commands.hpp"
#include "packlab/core/error.hpp"
#include "packlab/io/plot.hpp"

namespace packlab::cli {

void add_study(CLI::App& app) {
  struct Options {
    std::string spec;
    std::string out;
    int workers = 0;
    std::string scheduler;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("study",
                                 "Run a parameter study (option sweeps x seeds, or stages generate -> bond -> test) on "
                                 "local processes or a Dask cluster, resumable (docs/study.md)");
  cmd->add_option("spec", opt->spec, "Study file (TOML, docs/study.md)")->required();
  cmd->add_option("--out", opt->out, "Study folder (created; rerun the same command to resume)")->required();
  cmd->add_option("--workers", opt->workers, "Local worker processes (default: the number of cores)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--scheduler", opt->scheduler,
                  "Dask scheduler address tcp://HOST:PORT: run the tasks on its workers instead");
  cmd->add_flag("--quiet", opt->quiet, "No progress line");
  cmd->callback([opt] {
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) throw InputError("study: cannot find the packlab binary's path (/proc/self/exe)");
    const char* python_env = std::getenv("PACKLAB_PYTHON");
    const std::string python = python_env ? python_env : "/usr/bin/python3";
    const std::string package = io::python_package_dir().string();
    const char* old_path = std::getenv("PYTHONPATH");
    const std::string python_path = old_path && *old_path ? package + ":" + old_path : package;
    ::setenv("PYTHONPATH", python_path.c_str(), 1);
    std::vector<std::string> args = {python,  "-m",     "packlab.studies", opt->spec,
                                     "--out", opt->out, "--packlab",       self.string()};
    if (opt->workers > 0) args.insert(args.end(), {"--workers", std::to_string(opt->workers)});
    if (!opt->scheduler.empty()) args.insert(args.end(), {"--scheduler", opt->scheduler});
    if (opt->quiet) args.emplace_back("--quiet");
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(python.c_str(), argv.data());
    throw InputError(
        fmt::format("study: cannot run {} ({}): set PACKLAB_PYTHON to a python3", python, std::strerror(errno)));
  });
}

}  // namespace packlab::cli
