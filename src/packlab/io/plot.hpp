// PNG plots come from one place, the Python package packlab.plot (matplotlib): the command
// line writes its CSV tables first, then runs `python3 -m packlab.plot KIND ARGS --out PNG`.
// Where Python or matplotlib is missing it says so once on stderr and the run still succeeds.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace packlab::io {

struct PlotOptions {
  bool enabled = true;  // false: --no-plots
};

// Returns true when the PNG was written. Never throws for a missing Python/matplotlib.
bool make_plot(const std::string& kind, const std::vector<std::string>& args, const std::filesystem::path& png,
               const PlotOptions& options = {});

// The folder holding the `packlab` Python package: env PACKLAB_PYTHONPATH, else PREFIX/lib/
// packlab/python beside an installed binary (PREFIX/bin/packlab), else the sources' python/.
std::filesystem::path python_package_dir();

}  // namespace packlab::io
