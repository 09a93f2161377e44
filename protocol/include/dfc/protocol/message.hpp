#pragma once
// A protocol v1 message: the JSON header's fields plus its binary arrays (SPEC.md §3).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "dfc/protocol/array.hpp"
#include "dfc/protocol/error_code.hpp"

namespace dfc::protocol {

inline constexpr std::string_view kProtocolName = "dfc";
inline constexpr int kVersionMajor = 1;
inline constexpr int kVersionMinor = 8;
/// Largest advance.n_steps (SPEC.md §4); the coupler's scenario keys that set
/// steps per exchange are bounded by it, so `check` refuses what `run` would.
inline constexpr std::int64_t kMaxStepsPerAdvance = 1'000'000'000;
[[nodiscard]] std::string version_string();  ///< "1.0"

/// Message types of v1 (SPEC.md §4). Requests, then replies.
namespace type {
inline constexpr std::string_view hello = "hello";
inline constexpr std::string_view configure = "configure";
inline constexpr std::string_view get_interface = "get_interface";
inline constexpr std::string_view set_interface = "set_interface";
inline constexpr std::string_view advance = "advance";
inline constexpr std::string_view query = "query";
inline constexpr std::string_view snapshot = "snapshot";
inline constexpr std::string_view checkpoint = "checkpoint";  ///< 1.3, capability checkpoint
inline constexpr std::string_view restore = "restore";        ///< 1.3, capability checkpoint
inline constexpr std::string_view ping = "ping";
inline constexpr std::string_view shutdown = "shutdown";

inline constexpr std::string_view hello_ok = "hello_ok";
inline constexpr std::string_view configured = "configured";
inline constexpr std::string_view interface = "interface";
inline constexpr std::string_view ok = "ok";
inline constexpr std::string_view advanced = "advanced";
inline constexpr std::string_view monitors = "monitors";
inline constexpr std::string_view snapshot_data = "snapshot_data";
inline constexpr std::string_view checkpointed = "checkpointed";
inline constexpr std::string_view restored = "restored";
inline constexpr std::string_view pong = "pong";
inline constexpr std::string_view bye = "bye";
inline constexpr std::string_view error = "error";
}  // namespace type

struct Message {
  std::string type;
  std::string version = version_string();  ///< "MAJOR.MINOR" the sender speaks
  std::int64_t seq = 0;                     ///< sender's sequence number, >= 0
  std::optional<std::int64_t> reply_to;     ///< replies: the seq of the request
  std::optional<std::int64_t> step;         ///< advance/advanced: integer step count
  nlohmann::json body = nlohmann::json::object();
  std::vector<Array> arrays;
};

/// An `error` reply to `request_seq` (may be absent when the request could not be parsed).
[[nodiscard]] Message make_error(std::optional<std::int64_t> request_seq, ErrorCode code, const std::string& message,
                                 const std::string& key = {});

/// Major and minor of a "MAJOR.MINOR" string; nullopt if malformed.
[[nodiscard]] std::optional<std::pair<int, int>> parse_version(std::string_view text);

}  // namespace dfc::protocol
