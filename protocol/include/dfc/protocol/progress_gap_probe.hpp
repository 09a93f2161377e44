#pragma once
// ProgressGapProbe: how long a server's main thread goes, inside a request,
// without moving its work counter (dfc::work_progress, SPEC.md §9.1). The
// longest such gap is what run.stall_timeout_s must exceed; this measures it
// on a real run. A server runs one when DFC_PROGRESS_GAPS is set in its
// environment (to anything but empty) and prints on stderr, when it ends:
//   "dem_server: longest gap between work-progress bumps inside a request:
//    0.412 s (request 3); 18211 bumps in all"
#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

#include "dfc/protocol/heartbeat_responder.hpp"

namespace dfc::protocol {

class ProgressGapProbe {
 public:
  /// The environment variable that turns the probe on.
  static constexpr const char* kVariable = "DFC_PROGRESS_GAPS";

  /// Samples the counter and `liveness` (which says when a request is being
  /// handled) every few milliseconds from a thread of its own, until destroyed.
  /// `server_name` starts the line it prints.
  ProgressGapProbe(const Liveness& liveness, std::string server_name);
  ProgressGapProbe(const ProgressGapProbe&) = delete;
  ProgressGapProbe& operator=(const ProgressGapProbe&) = delete;
  /// Stops the sampling thread and prints the longest gap.
  ~ProgressGapProbe();

 private:
  void sample(std::stop_token stop, const Liveness& liveness) noexcept;

  std::string server_name_;
  double longest_s_ = 0.0;           ///< written by the sampling thread only, read after it joined
  std::int64_t longest_request_ = 0;  ///< 1-based number of the request the longest gap was in
  std::jthread thread_;              ///< last: starts after the members it writes exist
};

}  // namespace dfc::protocol
