#pragma once
// Assertions about replies, shared by the checks. Each throws CheckFailure
// with a sentence naming what was expected and what arrived.
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "check.hpp"
#include "dfc/protocol/message.hpp"

namespace dfc::conformance {

/// "'pong'" or "error OUT_OF_ORDER (\"...\")": what a reply was, for failure messages.
[[nodiscard]] std::string describe(const protocol::Message& reply);

/// The reply is of `type` (and, when `reply_to` is given, answers that seq).
void expect_type(const protocol::Message& reply, std::string_view type, std::optional<std::int64_t> reply_to = std::nullopt);

/// The reply is an `error` with one of `codes` and a non-empty message.
void expect_error(const protocol::Message& reply, std::initializer_list<std::string_view> codes);

/// The array `name` exists with `dtype` and `shape` (an extent of -1 matches
/// any length) and, for f64, only finite values. Returns it.
const protocol::Array& expect_array(const protocol::Message& reply, std::string_view name, protocol::DType dtype,
                                    const std::vector<std::int64_t>& shape);

/// `monitors` is an object of numbers or [x, y, z] numeric arrays (SPEC.md §6.3).
void expect_monitors(const nlohmann::json& monitors, std::string_view where);

/// The header `step` of the reply equals `step`.
void expect_step(const protocol::Message& reply, std::int64_t step);

[[nodiscard]] std::string shape_text(const std::vector<std::int64_t>& shape);

}  // namespace dfc::conformance
