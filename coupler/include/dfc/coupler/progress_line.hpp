#pragma once
// ProgressLine: one status line with an ETA for long runs. On a terminal it is
// rewritten in place; otherwise a line is printed every 10 % and at least once a minute, so logs
// stay short and a long run still shows it is alive.
#include <chrono>
#include <cstdint>
#include <iosfwd>
#include <string>

namespace dfc::coupler {

class ProgressLine {
 public:
  ProgressLine(std::ostream& out, std::string label, std::int64_t total, bool enabled);
  /// Reports `done` of `total` units with a short free-form detail text.
  void update(std::int64_t done, const std::string& detail);
  /// Ends the line (a newline on terminals).
  void finish();

 private:
  std::ostream& out_;
  std::string label_;
  std::int64_t total_;
  bool enabled_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_print_;
  std::int64_t last_decile_ = -1;
  bool open_line_ = false;
};

/// "1 h 02 min", "3 min 05 s", "42 s".
[[nodiscard]] std::string format_duration(double seconds);

}  // namespace dfc::coupler
