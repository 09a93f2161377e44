#include "dfc/common/durations.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dfc {

std::chrono::milliseconds milliseconds_from_seconds(double seconds) noexcept {
  if (!(seconds > 0.0)) return std::chrono::milliseconds(0);
  const double clamped = std::min(seconds, kLongestWaitSeconds);
  return std::chrono::milliseconds(static_cast<long long>(std::ceil(clamped * 1000.0)));
}

std::string seconds_text(std::chrono::milliseconds duration) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", static_cast<double>(duration.count()) / 1000.0);
  return text;
}

}  // namespace dfc
