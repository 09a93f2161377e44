#pragma once
// Helpers shared by the codec tests: frames from header text and arrays,
// and typed arrays of any dtype.
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "dfc/protocol/codec.hpp"

namespace dfc::protocol::testing {

/// Byte views of `texts` (frame 0 = header, then arrays), valid while `texts` lives.
inline std::vector<std::span<const std::byte>> views_of(const std::vector<std::string>& texts) {
  std::vector<std::span<const std::byte>> views;
  for (const auto& text : texts) views.emplace_back(reinterpret_cast<const std::byte*>(text.data()), text.size());
  return views;
}

/// Encodes `message` into frames as a sender would, then decodes them.
inline Message round_trip(const Message& message, const Limits& limits = {}) {
  std::vector<std::string> frames{encode_header(message)};
  for (const auto& array : message.arrays) frames.emplace_back(reinterpret_cast<const char*>(array.bytes.data()), array.bytes.size());
  return decode(views_of(frames), limits);
}

/// Decodes a header text plus raw array frames.
inline Message decode_texts(const std::vector<std::string>& frames, const Limits& limits = {}) { return decode(views_of(frames), limits); }

template <typename T>
Array typed_array(std::string name, DType dtype, std::vector<std::int64_t> shape, const std::vector<T>& values) {
  Array array{std::move(name), dtype, std::move(shape), std::vector<std::byte>(values.size() * sizeof(T))};
  if (!values.empty()) std::memcpy(array.bytes.data(), values.data(), array.bytes.size());
  return array;
}

/// The error code decode() raises for `frames`; fails the test if it decodes.
inline ErrorCode decode_error_code(const std::vector<std::string>& frames, const Limits& limits = {}) {
  try {
    (void)decode_texts(frames, limits);
  } catch (const DecodeError& e) {
    return e.code();
  }
  throw std::logic_error("decode accepted frames it should have refused: " + (frames.empty() ? std::string() : frames[0].substr(0, 200)));
}

}  // namespace dfc::protocol::testing
