#include "packlab/io/report.hpp"

#include "packlab/io/atomic_file.hpp"

namespace packlab::io {

std::string version() { return PACKLAB_VERSION; }

nlohmann::json report_header(const std::string& command) {
  return {{"packlab_version", version()}, {"command", command}};
}

void write_report(const std::filesystem::path& path, const nlohmann::json& report) {
  write_text_atomically(path, report.dump(2) + "\n");
}

}  // namespace packlab::io
