#pragma once
// A named, typed, shaped array as carried in one binary frame (SPEC.md §3).
// Storage is the frame's little-endian bytes; typed views copy out so that
// callers never depend on the alignment of a received ZeroMQ buffer.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace dfc::protocol {

static_assert(std::endian::native == std::endian::little, "the wire format is little-endian; big-endian hosts need byte swapping");

enum class DType { f64, f32, i64, i32, u8 };

[[nodiscard]] std::string_view dtype_name(DType dtype) noexcept;
[[nodiscard]] std::optional<DType> dtype_from_name(std::string_view name) noexcept;
[[nodiscard]] std::size_t dtype_size(DType dtype) noexcept;

struct Array {
  std::string name;
  DType dtype = DType::f64;
  std::vector<std::int64_t> shape;
  std::vector<std::byte> bytes;

  [[nodiscard]] std::int64_t element_count() const noexcept;

  [[nodiscard]] static Array from_f64(std::string name, std::vector<std::int64_t> shape, std::span<const double> values);
  [[nodiscard]] static Array from_i64(std::string name, std::vector<std::int64_t> shape, std::span<const std::int64_t> values);
  [[nodiscard]] static Array from_bytes(std::string name, std::span<const std::byte> values);

  /// Values as doubles; throws ProtocolError(BAD_ARRAY) if dtype is not f64.
  [[nodiscard]] std::vector<double> to_f64() const;
  /// Values as int64; throws ProtocolError(BAD_ARRAY) if dtype is not i64.
  [[nodiscard]] std::vector<std::int64_t> to_i64() const;
};

/// The array called `name` in `arrays`, or nullptr.
[[nodiscard]] const Array* find_array(std::span<const Array> arrays, std::string_view name) noexcept;
/// The array called `name`, checked to be f64 of shape [rows, cols] (cols = 0: 1-D of length rows).
/// Throws ProtocolError(BAD_ARRAY) naming the array and the expected shape.
[[nodiscard]] std::vector<double> require_f64(std::span<const Array> arrays, std::string_view name, std::int64_t rows, std::int64_t cols);

/// Throws ProtocolError(BAD_ARRAY) naming the first array of `inputs` not in
/// `allowed` (SPEC.md §6.1: a server refuses input arrays it does not take);
/// `who` names the receiver in the message ("a driven fdm_server").
void require_only(std::span<const Array> inputs, std::initializer_list<std::string_view> allowed, const std::string& who);

}  // namespace dfc::protocol
