#include "dfc/protocol/array.hpp"

#include <algorithm>
#include <cstring>

#include "dfc/common/work_progress.hpp"
#include "dfc/protocol/error_code.hpp"

namespace dfc::protocol {

std::string_view dtype_name(DType dtype) noexcept {
  switch (dtype) {
    case DType::f64: return "f64";
    case DType::f32: return "f32";
    case DType::i64: return "i64";
    case DType::i32: return "i32";
    case DType::u8: return "u8";
  }
  return "?";
}

std::optional<DType> dtype_from_name(std::string_view name) noexcept {
  for (DType d : {DType::f64, DType::f32, DType::i64, DType::i32, DType::u8})
    if (dtype_name(d) == name) return d;
  return std::nullopt;
}

std::size_t dtype_size(DType dtype) noexcept {
  switch (dtype) {
    case DType::f64:
    case DType::i64: return 8;
    case DType::f32:
    case DType::i32: return 4;
    case DType::u8: return 1;
  }
  return 1;
}

std::int64_t Array::element_count() const noexcept {
  // A zero extent first: decode() accepts an empty array of any other extents
  // ([2^32, 2^31, 0] holds no bytes), whose running product would overflow.
  if (std::find(shape.begin(), shape.end(), 0) != shape.end()) return 0;
  std::int64_t count = 1;
  for (const auto extent : shape) count *= extent;
  return count;
}

namespace {
template <typename T>
Array make_array(std::string name, DType dtype, std::vector<std::int64_t> shape, std::span<const T> values) {
  Array array{std::move(name), dtype, std::move(shape), {}};
  if (array.element_count() != std::int64_t(values.size()))
    throw ProtocolError(ErrorCode::internal, "array '" + array.name + "': shape does not match the number of values");
  array.bytes.resize(values.size_bytes());
  if (!values.empty()) std::memcpy(array.bytes.data(), values.data(), values.size_bytes());
  work_progress::advance();  // a snapshot of a large body is a series of arrays of millions of rows, each built before it
  return array;
}

template <typename T>
std::vector<T> copy_out(const Array& array, DType expected) {
  if (array.dtype != expected)
    throw ProtocolError(ErrorCode::bad_array, "array '" + array.name + "' has dtype " + std::string(dtype_name(array.dtype)) +
                                                  ", expected " + std::string(dtype_name(expected)));
  std::vector<T> values(array.bytes.size() / sizeof(T));
  if (!values.empty()) std::memcpy(values.data(), array.bytes.data(), values.size() * sizeof(T));
  return values;
}

std::string shape_text(const std::vector<std::int64_t>& shape) {
  std::string text = "[";
  for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? "," : "") + std::to_string(shape[i]);
  return text + "]";
}
}  // namespace

Array Array::from_f64(std::string name, std::vector<std::int64_t> shape, std::span<const double> values) {
  return make_array(std::move(name), DType::f64, std::move(shape), values);
}

Array Array::from_i64(std::string name, std::vector<std::int64_t> shape, std::span<const std::int64_t> values) {
  return make_array(std::move(name), DType::i64, std::move(shape), values);
}

Array Array::from_bytes(std::string name, std::span<const std::byte> values) {
  return make_array(std::move(name), DType::u8, {std::int64_t(values.size())}, values);
}

std::vector<double> Array::to_f64() const { return copy_out<double>(*this, DType::f64); }
std::vector<std::int64_t> Array::to_i64() const { return copy_out<std::int64_t>(*this, DType::i64); }

const Array* find_array(std::span<const Array> arrays, std::string_view name) noexcept {
  for (const auto& array : arrays)
    if (array.name == name) return &array;
  return nullptr;
}

std::vector<double> require_f64(std::span<const Array> arrays, std::string_view name, std::int64_t rows, std::int64_t cols) {
  const std::vector<std::int64_t> expected = cols == 0 ? std::vector<std::int64_t>{rows} : std::vector<std::int64_t>{rows, cols};
  const Array* array = find_array(arrays, name);
  if (array == nullptr)
    throw ProtocolError(ErrorCode::bad_array, "missing input array '" + std::string(name) + "' (f64 " + shape_text(expected) + ")");
  if (array->dtype != DType::f64 || array->shape != expected)
    throw ProtocolError(ErrorCode::bad_array, "array '" + std::string(name) + "' is " + std::string(dtype_name(array->dtype)) + " " +
                                                  shape_text(array->shape) + ", expected f64 " + shape_text(expected));
  return array->to_f64();
}

void require_only(std::span<const Array> inputs, std::initializer_list<std::string_view> allowed, const std::string& who) {
  for (const Array& array : inputs)
    if (std::find(allowed.begin(), allowed.end(), array.name) == allowed.end()) {
      std::string list;
      for (const auto name : allowed) list += (list.empty() ? "'" : ", '") + std::string(name) + "'";
      throw ProtocolError(ErrorCode::bad_array, "unexpected input array '" + array.name + "': " + who + " takes " +
                                                    (list.empty() ? std::string("no input arrays") : list));
    }
}

}  // namespace dfc::protocol
