#pragma once
// Seconds from input (scenario keys, command-line options) to std::chrono.
//
// steady_clock counts nanoseconds in 64 bits (about 292 years), so "now +
// 1e10 s" already wraps to the past and a cast of 1e300 s is undefined. Every
// wait the user sets is bounded by kLongestWaitSeconds where it is read, and
// converted here, saturating, so no conversion can overflow.
#include <chrono>
#include <string>

namespace dfc {

/// Longest wait any input may ask for: 1e6 s (11.6 days), far beyond any
/// sensible deadline, far below where time arithmetic overflows.
inline constexpr double kLongestWaitSeconds = 1e6;

/// `seconds` as milliseconds, rounded up, clamped to [0, kLongestWaitSeconds]
/// (NaN gives 0).
[[nodiscard]] std::chrono::milliseconds milliseconds_from_seconds(double seconds) noexcept;

/// A wait for messages, in the seconds the user gave it: "2 s", "0.5 s", "1800 s".
[[nodiscard]] std::string seconds_text(std::chrono::milliseconds duration);

}  // namespace dfc
