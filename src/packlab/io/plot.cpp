#include "packlab/io/plot.hpp"

#include <fmt/format.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>

namespace packlab::io {

namespace {

// Single quotes for the shell, with embedded quotes escaped.
std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') {
      out.append("'\\''");
    } else {
      out.push_back(c);
    }
  }
  out.push_back('\'');
  return out;
}

bool warned = false;  // say "no plots" once per process

}  // namespace

std::filesystem::path python_package_dir() {
  if (const char* env = std::getenv("PACKLAB_PYTHONPATH")) return env;
  // An installed packlab (`cmake --install`, docs/install.md): PREFIX/bin/packlab finds the
  // package in PREFIX/lib/packlab/python (the folder CMakeLists.txt installs it into), wherever
  // the prefix was moved, and whether or not the sources it was built from still exist.
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path installed = exe.parent_path().parent_path() / "lib" / "packlab" / "python";
    if (std::filesystem::exists(installed / "packlab" / "plot" / "__main__.py", ec)) return installed;
  }
  // The build tree: the sources' python/ folder.
  return PACKLAB_PYTHON_DIR;
}

bool make_plot(const std::string& kind, const std::vector<std::string>& args, const std::filesystem::path& png,
               const PlotOptions& options) {
  if (!options.enabled) return false;
  const char* python = std::getenv("PACKLAB_PYTHON");
  std::string cmd =
      fmt::format("PYTHONPATH={}${{PYTHONPATH:+:$PYTHONPATH}} {} -m packlab.plot {}",
                  quote(python_package_dir().string()), python ? quote(python) : "/usr/bin/python3", quote(kind));
  for (const auto& a : args) {
    cmd.push_back(' ');
    cmd.append(quote(a));
  }
  cmd.append(" --out ");
  cmd.append(quote(png.string()));
  cmd.append(" 2>&1");
  FILE* pipe = ::popen(cmd.c_str(), "r");
  std::string output;
  if (pipe) {
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  }
  const int status = pipe ? ::pclose(pipe) : -1;
  if (status == 0) return true;
  if (!warned) {
    warned = true;
    const bool missing = output.find("No module named") != std::string::npos || status == -1 ||
                         (WIFEXITED(status) && WEXITSTATUS(status) == 127);
    std::fprintf(stderr, "packlab: note: plots skipped (%s); tables are written, use --no-plots to silence this\n",
                 missing ? "python3 with matplotlib not found" : "the plotting script failed");
    if (!missing && !output.empty()) std::fprintf(stderr, "%s", output.c_str());
  }
  return false;
}

}  // namespace packlab::io
