#include "fuzz_input.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace dfc::fuzz {

std::vector<std::string_view> split_messages(std::string_view input) {
  std::vector<std::string_view> messages;
  for (;;) {
    const auto at = input.find(kMessageSeparator);
    messages.push_back(input.substr(0, at));
    if (at == std::string_view::npos) return messages;
    input.remove_prefix(at + kMessageSeparator.size());
  }
}

FuzzFrames read_frames(std::string_view message) {
  FuzzFrames out{{}, protocol::Limits{}};
  if (message.empty()) return out;
  const auto control = static_cast<unsigned char>(message.front());
  message.remove_prefix(1);
  if ((control & kTightLimitsBit) != 0) out.limits = kTightLimits;
  const std::size_t array_frames = control & 3u;
  std::vector<std::size_t> lengths;
  for (std::size_t k = 0; k < array_frames; ++k) {
    std::size_t length = 0;
    if (message.size() >= 2) {
      length = std::size_t(static_cast<unsigned char>(message[0])) | std::size_t(static_cast<unsigned char>(message[1])) << 8;
      message.remove_prefix(2);
    } else {
      message = {};
    }
    lengths.push_back(length);
  }
  const auto bytes = [](std::string_view text) { return std::as_bytes(std::span(text.data(), text.size())); };
  std::vector<std::span<const std::byte>> arrays;
  for (const std::size_t length : lengths) {
    const std::size_t taken = std::min(length, message.size());
    arrays.push_back(bytes(message.substr(0, taken)));
    message.remove_prefix(taken);
  }
  out.frames.push_back(bytes(message));
  out.frames.insert(out.frames.end(), arrays.begin(), arrays.end());
  return out;
}

std::string write_frames(std::string_view header, std::span<const std::string> arrays, bool tight_limits) {
  if (arrays.size() > 3) throw std::invalid_argument("write_frames: at most 3 array frames");
  std::string out(1, static_cast<char>(arrays.size() | (tight_limits ? kTightLimitsBit : 0u)));
  for (const std::string& array : arrays) {
    if (array.size() > 0xffff) throw std::invalid_argument("write_frames: an array frame is limited to 64 KiB");
    out += static_cast<char>(array.size() & 0xff);
    out += static_cast<char>(array.size() >> 8);
  }
  for (const std::string& array : arrays) out += array;
  out += header;
  return out;
}

std::string join_messages(std::span<const std::string> messages) {
  std::string out;
  for (std::size_t k = 0; k < messages.size(); ++k) {
    if (messages[k].find(kMessageSeparator) != std::string::npos) throw std::invalid_argument("join_messages: a message holds the separator");
    if (k > 0) out += kMessageSeparator;
    out += messages[k];
  }
  return out;
}

}  // namespace dfc::fuzz
