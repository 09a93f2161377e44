#pragma once
// The byte layout the protocol fuzzer reads. One input holds several
// messages, so that a sequence (hello, configure, advance, ...) reaches the
// later states of the session; each message is split into 1-4 frames, so
// that mutations reach array frames and every frame-count check of the codec.
//
//   input   = message (kMessageSeparator message)*
//   message = ""                              a message of no frames at all
//           | control lengths arrays header
//   control = 1 byte: bits 0-1 give the number of array frames (0-3);
//             bit 7 decodes under tight limits (kTightLimits), so that the
//             TOO_LARGE paths are reached by inputs of a few hundred bytes
//   lengths = one little-endian uint16 per array frame (clamped to the bytes left)
//   arrays  = the array frames' bytes, in order
//   header  = every byte left: frame 0, the JSON header
//
// A separator rather than length prefixes between messages: the fuzzer's
// insertions and deletions inside one message then leave the others intact.
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "dfc/protocol/codec.hpp"

namespace dfc::fuzz {

inline constexpr std::string_view kMessageSeparator = "\n#dfc#\n";
inline constexpr unsigned char kTightLimitsBit = 0x80;
/// Small enough that a fuzzer input of a few hundred bytes crosses each limit.
inline constexpr protocol::Limits kTightLimits{.max_header_bytes = 512, .max_array_bytes = 96, .max_arrays = 2};

/// The messages of `input`, split at kMessageSeparator (views into `input`).
[[nodiscard]] std::vector<std::string_view> split_messages(std::string_view input);

/// One message's frames (views into the message's bytes) and the limits to decode them with.
struct FuzzFrames {
  std::vector<std::span<const std::byte>> frames;
  protocol::Limits limits;
};
[[nodiscard]] FuzzFrames read_frames(std::string_view message);

/// The inverse of read_frames, for the seed-corpus generator: `header` as
/// frame 0 and `arrays` (at most 3, each under 64 KiB) as frames 1..k.
[[nodiscard]] std::string write_frames(std::string_view header, std::span<const std::string> arrays, bool tight_limits = false);
/// `messages` joined by kMessageSeparator; none may contain it.
[[nodiscard]] std::string join_messages(std::span<const std::string> messages);

}  // namespace dfc::fuzz
