#pragma once
// Encoding and decoding of v1 messages to and from frames (SPEC.md §3).
// The codec never touches a socket: frames are byte strings / byte views.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "dfc/protocol/message.hpp"

namespace dfc::protocol {

/// Limits a receiver enforces (SPEC.md §8); a server announces its own in hello_ok.
struct Limits {
  std::size_t max_header_bytes = 1u << 20;      ///< 1 MiB
  std::size_t max_array_bytes = 256u << 20;     ///< 256 MiB per array frame
  std::size_t max_arrays = 64;                  ///< array frames per message
};

/// Frame 0 (the JSON header) as text; the arrays' bytes follow as frames 1..k.
[[nodiscard]] std::string encode_header(const Message& message);

/// Raised when frames do not form a valid message; carries the request's seq
/// when the header was readable enough to find it, so the error reply can name it.
class DecodeError : public ProtocolError {
 public:
  DecodeError(ErrorCode code, const std::string& message, std::optional<std::int64_t> seq)
      : ProtocolError(code, message), seq_(seq) {}
  [[nodiscard]] std::optional<std::int64_t> seq() const noexcept { return seq_; }

 private:
  std::optional<std::int64_t> seq_;
};

/// Decodes frames (header first). Never allocates more than the frames' own
/// size: array shapes are checked against the frame lengths before any copy.
[[nodiscard]] Message decode(std::span<const std::span<const std::byte>> frames, const Limits& limits);

}  // namespace dfc::protocol
