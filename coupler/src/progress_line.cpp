#include "dfc/coupler/progress_line.hpp"

#include <unistd.h>

#include <cstdio>
#include <ostream>

namespace dfc::coupler {

std::string format_duration(double seconds) {
  char text[64];
  const auto s = static_cast<long>(seconds + 0.5);
  if (s >= 3600) std::snprintf(text, sizeof text, "%ld h %02ld min", s / 3600, (s % 3600) / 60);
  else if (s >= 60) std::snprintf(text, sizeof text, "%ld min %02ld s", s / 60, s % 60);
  else if (seconds >= 10) std::snprintf(text, sizeof text, "%ld s", s);
  else std::snprintf(text, sizeof text, "%.1f s", seconds);
  return text;
}

ProgressLine::ProgressLine(std::ostream& out, std::string label, std::int64_t total, bool enabled)
    : out_(out),
      label_(std::move(label)),
      total_(total > 0 ? total : 1),
      enabled_(enabled),
      terminal_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

void ProgressLine::update(std::int64_t done, const std::string& detail) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const std::int64_t decile = done * 10 / total_;
  // In a log: every 10 %, and at least once a minute (a run that stops on
  // equilibrium may end long before its first 10 %).
  const bool due = terminal_ ? (now - last_print_ > std::chrono::milliseconds(250) || done == total_)
                             : decile != last_decile_ || now - last_print_ >= std::chrono::seconds(60);
  if (!due) return;
  last_print_ = now;
  last_decile_ = decile;
  const double fraction = double(done) / double(total_);
  const std::string eta = done > 0 ? format_duration(elapsed * (1.0 - fraction) / fraction) : "?";
  char head[160];
  std::snprintf(head, sizeof head, "[%s] %lld/%lld (%3.0f%%) ", label_.c_str(), static_cast<long long>(done),
                static_cast<long long>(total_), 100.0 * fraction);
  const std::string line = std::string(head) + detail + "  elapsed " + format_duration(elapsed) + ", ETA " + eta;
  if (terminal_) {
    out_ << "\r" << line << "\033[K" << std::flush;
    open_line_ = true;
  } else {
    out_ << line << "\n" << std::flush;
  }
}

void ProgressLine::finish() {
  if (open_line_) out_ << "\n" << std::flush;
  open_line_ = false;
}

}  // namespace dfc::coupler
