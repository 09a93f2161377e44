#include "dfc/common/echo.hpp"

namespace dfc {

std::string echoed(std::string_view value, std::size_t max_bytes) {
  if (value.size() <= max_bytes) return std::string(value);
  const std::string tail = "\xE2\x80\xA6 (" + std::to_string(value.size()) + " bytes)";  // "…"
  std::size_t keep = max_bytes > tail.size() ? max_bytes - tail.size() : 0;
  // Not in the middle of a UTF-8 character: back off its continuation bytes (10xxxxxx).
  while (keep > 0 && (static_cast<unsigned char>(value[keep]) & 0xC0U) == 0x80U) --keep;
  return std::string(value.substr(0, keep)) + tail;
}

}  // namespace dfc
