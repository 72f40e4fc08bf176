#include "packlab/core/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace packlab {

Progress::Progress(std::string label, long total, bool enabled)
    : label_(std::move(label)), total_(total), enabled_(enabled), tty_(::isatty(STDERR_FILENO) != 0),
      start_(Clock::now()), last_(start_) {}

Progress::~Progress() { finish(); }

double Progress::elapsed_seconds() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

void Progress::update(long done, const std::string& detail) {
  if (!enabled_) return;
  const auto now = Clock::now();
  const double since_start = std::chrono::duration<double>(now - start_).count();
  const double since_last = std::chrono::duration<double>(now - last_).count();
  // A terminal gets a line refreshed twice a second; a log file one line every 5 s.
  if (since_start < 1.0 || since_last < (tty_ ? 0.5 : 5.0)) return;
  last_ = now;
  const double rate = static_cast<double>(done) / since_start;
  std::string eta = "?";
  if (total_ > 0 && rate > 0.0) eta = fmt::format("{:.0f} s", static_cast<double>(total_ - done) / rate);
  const std::string line = fmt::format("{}: {}/{} ({:.3g}/s){}{} ETA {}", label_, done, total_, rate,
                                       detail.empty() ? "" : ", ", detail, eta);
  std::fprintf(stderr, tty_ ? "\r%s\033[K" : "%s\n", line.c_str());
  std::fflush(stderr);
  printed_ = true;
}

void Progress::finish() {
  if (printed_ && tty_) std::fputc('\n', stderr);
  printed_ = false;
}

}  // namespace packlab
