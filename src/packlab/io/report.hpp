// JSON reports (nlohmann-json): every run that writes a folder writes DIR/report.json with
// the parameters, seed, version, results and seconds.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace packlab::io {

std::string version();

// {"packlab_version": ..., "command": command}
nlohmann::json report_header(const std::string& command);

// Writes the report atomically, pretty-printed, with full double precision.
void write_report(const std::filesystem::path& path, const nlohmann::json& report);

}  // namespace packlab::io
