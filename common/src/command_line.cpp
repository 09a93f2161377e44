#include "dfc/common/command_line.hpp"

#include <charconv>
#include <cmath>

#include "dfc/common/errors.hpp"

namespace dfc {

double parse_number_option(std::string_view option, const std::string& text, Bounds bounds) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  const bool below = bounds.min_exclusive ? !(value > bounds.min) : !(value >= bounds.min);
  if (text.empty() || error != std::errc() || stop != end || !std::isfinite(value) || below || !(value <= bounds.max))
    throw UserError("option " + std::string(option) + " takes " + describe_bounds(bounds) + ", got '" + text + "'");
  return value;
}

std::uint64_t parse_count_option(std::string_view option, const std::string& text, std::uint64_t min_value, std::uint64_t max_value) {
  std::uint64_t value = 0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (text.empty() || error != std::errc() || stop != end || value < min_value || value > max_value)
    throw UserError("option " + std::string(option) + " takes a whole number in [" + std::to_string(min_value) + ", " +
                    std::to_string(max_value) + "], got '" + text + "'");
  return value;
}

}  // namespace dfc
