#include "dfc/protocol/error_code.hpp"

#include <array>
#include <utility>

namespace dfc::protocol {

namespace {
constexpr std::array<std::pair<ErrorCode, std::string_view>, 12> kNames{{
    {ErrorCode::bad_message, "BAD_MESSAGE"},
    {ErrorCode::unknown_type, "UNKNOWN_TYPE"},
    {ErrorCode::version_mismatch, "VERSION_MISMATCH"},
    {ErrorCode::out_of_order, "OUT_OF_ORDER"},
    {ErrorCode::bad_array, "BAD_ARRAY"},
    {ErrorCode::too_large, "TOO_LARGE"},
    {ErrorCode::step_mismatch, "STEP_MISMATCH"},
    {ErrorCode::bad_config, "BAD_CONFIG"},
    {ErrorCode::unsupported, "UNSUPPORTED"},
    {ErrorCode::solver_failure, "SOLVER_FAILURE"},
    {ErrorCode::bad_checkpoint, "BAD_CHECKPOINT"},
    {ErrorCode::internal, "INTERNAL"},
}};
}  // namespace

std::string_view error_code_name(ErrorCode code) noexcept {
  for (const auto& [c, name] : kNames)
    if (c == code) return name;
  return "INTERNAL";
}

std::optional<ErrorCode> error_code_from_name(std::string_view name) noexcept {
  for (const auto& [c, n] : kNames)
    if (n == name) return c;
  return std::nullopt;
}

}  // namespace dfc::protocol
