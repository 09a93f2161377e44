#pragma once
// Input echoed back in an error or a log line, cut to a readable length.
// A message names what it refuses ("unknown key \"...\""), but the value comes
// from outside: a key 200 kB long, echoed in full, buries the sentence around
// it (and a reply or log line grows with it). Every message that quotes input
// passes it through echoed(), so that one rule bounds them all.
#include <cstddef>
#include <string>
#include <string_view>

namespace dfc {

/// The longest echo of a value in a message, in bytes (a key, a value, a
/// message type, a file name: each readable on one line). Key paths are cut
/// key by key, so that a path keeps its declared keys whole.
inline constexpr std::size_t kMaxEchoBytes = 80;

/// The longest echo of a file path or endpoint: a real one (an absolute path
/// deep in a cluster's scratch space) stays whole.
inline constexpr std::size_t kMaxEchoedPathBytes = 400;

/// The longest echo of another program's message (a server's error reply):
/// a whole sentence, but not a reply that grew without bound.
inline constexpr std::size_t kMaxEchoedMessageBytes = 2000;

/// `value` if at most `max_bytes` long; otherwise its beginning, cut at a
/// UTF-8 character boundary, followed by "… (N bytes)", N the full length.
/// The result is never longer than `max_bytes` (for max_bytes >= 40), so
/// echoing an echo changes nothing.
[[nodiscard]] std::string echoed(std::string_view value, std::size_t max_bytes = kMaxEchoBytes);

}  // namespace dfc
