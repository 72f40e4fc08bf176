// One throttled progress line on stderr (steps, rate, a quantity, ETA) for work that runs
// longer than a second. Silent when disabled (--quiet) or before the first second.
#pragma once

#include <chrono>
#include <string>

namespace packlab {

class Progress {
 public:
  Progress(std::string label, long total, bool enabled);
  ~Progress();
  // `done` of `total` units finished; `detail` is appended (e.g. "unbalanced 3.1e-3").
  void update(long done, const std::string& detail = "");
  // Ends the line (if anything was printed).
  void finish();
  double elapsed_seconds() const;

 private:
  using Clock = std::chrono::steady_clock;
  std::string label_;
  long total_;
  bool enabled_;
  bool printed_ = false;
  bool tty_;
  Clock::time_point start_, last_;
};

}  // namespace packlab
