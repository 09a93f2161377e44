#include "dfc/protocol/progress_gap_probe.hpp"

#include <chrono>
#include <cstdio>
#include <iostream>

#include "dfc/common/work_progress.hpp"

namespace dfc::protocol {

namespace {
// The resolution of the measurement: far below the gaps that matter (seconds).
constexpr auto kSampleInterval = std::chrono::milliseconds(5);
}  // namespace

ProgressGapProbe::ProgressGapProbe(const Liveness& liveness, std::string server_name)
    : server_name_(std::move(server_name)), thread_([this, &liveness](std::stop_token stop) { sample(stop, liveness); }) {}

ProgressGapProbe::~ProgressGapProbe() {
  thread_.request_stop();
  thread_.join();
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.3f s", longest_s_);
  std::cerr << server_name_ << ": longest gap between work-progress bumps inside a request: " << seconds << " (request " << longest_request_
            << "); " << work_progress::current() << " bumps in all (" << kVariable << ")\n";
}

void ProgressGapProbe::sample(std::stop_token stop, const Liveness& liveness) noexcept {
  using Clock = std::chrono::steady_clock;
  std::int64_t last_count = work_progress::current();
  Clock::time_point since = Clock::now();
  bool was_busy = false;
  while (!stop.stop_requested()) {
    std::this_thread::sleep_for(kSampleInterval);
    const auto now = Clock::now();
    const std::int64_t count = work_progress::current();
    const bool busy = liveness.busy_seconds() >= 0.0;
    // A gap starts where a request starts or the counter last moved; an idle
    // server (waiting for the client) is not in one.
    if (!busy || !was_busy || count != last_count) {
      last_count = count;
      since = now;
    } else if (const double gap = std::chrono::duration<double>(now - since).count(); gap > longest_s_) {
      longest_s_ = gap;
      longest_request_ = liveness.handled() + 1;
    }
    was_busy = busy;
  }
}

}  // namespace dfc::protocol
