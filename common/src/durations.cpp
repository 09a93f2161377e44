#include "dfc/common/durations.hpp"

#include <algorithm>
#include <cmath>

namespace dfc {

std::chrono::milliseconds milliseconds_from_seconds(double seconds) noexcept {
  if (!(seconds > 0.0)) return std::chrono::milliseconds(0);
  const double clamped = std::min(seconds, kLongestWaitSeconds);
  return std::chrono::milliseconds(static_cast<long long>(std::ceil(clamped * 1000.0)));
}

}  // namespace dfc
