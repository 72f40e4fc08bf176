#include "packlab/io/atomic_file.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <exception>
#include <fstream>
#include <system_error>

#include "packlab/core/error.hpp"

namespace packlab::io {

void write_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
  const auto parent = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(parent))
    fail_input(fmt::format("cannot write {}: folder {} does not exist", path.string(), parent.string()));
  // Unique per process so two runs writing the same target never share a temporary.
  const auto tmp = parent / fmt::format(".{}.tmp{}", path.filename().string(), ::getpid());
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) fail_input(fmt::format("cannot write {}: cannot open a temporary file", path.string()));
      out.exceptions(std::ios::badbit | std::ios::failbit);
      write(out);
      out.flush();
    }
    std::filesystem::rename(tmp, path);
  } catch (const std::ios_base::failure&) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    fail_input(fmt::format("cannot write {}: write failed (disk full or no permission?)", path.string()));
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
}

void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  write_atomically(path, [&](std::ostream& out) { out << text; });
}

void ensure_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec)) {
    if (!std::filesystem::is_directory(dir, ec))
      fail_input(fmt::format("output folder {} exists and is not a folder", dir.string()));
    return;
  }
  std::filesystem::create_directories(dir, ec);
  if (ec) fail_input(fmt::format("cannot create output folder {}: {}", dir.string(), ec.message()));
}

OutputFolder::OutputFolder(std::filesystem::path dir) : dir_(std::move(dir)), exceptions_(std::uncaught_exceptions()) {
  std::error_code ec;
  created_ = !std::filesystem::exists(dir_, ec);
  ensure_directory(dir_);
}

OutputFolder::~OutputFolder() {
  if (!created_ || std::uncaught_exceptions() <= exceptions_) return;
  std::error_code ec;
  if (std::filesystem::is_empty(dir_, ec) && !ec) std::filesystem::remove(dir_, ec);
}

void check_writable_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail_input(fmt::format("{}: is a folder, not a file", path.string()));
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(dir, ec))
    fail_input(fmt::format("{}: the folder {} does not exist", path.string(), dir.string()));
  const std::filesystem::path probe = dir / fmt::format(".packlab-probe-{}", static_cast<long>(::getpid()));
  {
    std::ofstream out(probe, std::ios::binary);
    if (!out) fail_input(fmt::format("{}: cannot write in the folder {}", path.string(), dir.string()));
  }
  std::filesystem::remove(probe, ec);
}

}  // namespace packlab::io
