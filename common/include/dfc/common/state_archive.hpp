#pragma once
// StateWriter / StateReader: the bytes of a checkpoint (protocol/SPEC.md §4.7).
//
// A solver's checkpoint is a raw image of every member that changes while it
// runs, written in a fixed order and read back in the same order: restoring
// copies bits, it re-derives nothing, so a restored run continues bit for bit
// (a contact list read back has the order the search gave it, a rebuild falls
// on the same step). Values are stored in the machine's own byte order and
// sizes; the checkpoint header (the session's) refuses a file written by
// another solver version, and StateReader refuses one that is shorter than
// what it declares, so a damaged file is an error, never a wrong state.
//
//   StateWriter out;  out.value(step);  out.vector(positions);   // ... std::string bytes = out.take();
//   StateReader in(bytes, "dem_server state");  in.value(step);  in.vector(positions);  in.finish();
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "dfc/common/work_progress.hpp"

namespace dfc {

/// A checkpoint that cannot be read: truncated, damaged, or of another layout.
class StateFormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Types stored as their bytes. Trivially copyable types qualify; a fixed-size
/// type that is not (e.g. an Eigen vector) opts in by specialising this.
template <class T>
inline constexpr bool stored_as_bytes = std::is_trivially_copyable_v<T>;

class StateWriter {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(stored_as_bytes<T>, "StateWriter stores only types that are their bytes");
    bytes(&v, sizeof(T));
  }
  template <class T, class Allocator>
  void vector(const std::vector<T, Allocator>& v) {
    static_assert(stored_as_bytes<T>, "StateWriter stores only types that are their bytes");
    value(std::uint64_t(v.size()));
    if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
  }
  void vector(const std::vector<bool>& v);
  template <class T>
  void optional(const std::optional<T>& v) {
    value(std::uint8_t(v.has_value()));
    if (v) value(*v);
  }
  void string(std::string_view s);
  /// A section marker: a reader that lost its place fails here, naming `name`.
  /// Each section of a large state is a while in the making: the work counter moves (SPEC.md §9.1).
  void tag(std::string_view name) {
    string(name);
    work_progress::advance();
  }

  [[nodiscard]] std::size_t size() const noexcept { return out_.size(); }
  [[nodiscard]] std::string take() { return std::move(out_); }

 private:
  void bytes(const void* data, std::size_t n) { out_.append(static_cast<const char*>(data), n); }
  std::string out_;
};

class StateReader {
 public:
  /// `what` names the state in errors ("dem_server state").
  StateReader(std::string_view bytes, std::string what) : in_(bytes), what_(std::move(what)) {}

  template <class T>
  void value(T& v) {
    static_assert(stored_as_bytes<T>, "StateReader reads only types that are their bytes");
    std::memcpy(static_cast<void*>(&v), take(sizeof(T)), sizeof(T));
  }
  template <class T>
  [[nodiscard]] T value() {
    T v{};
    value(v);
    return v;
  }
  template <class T, class Allocator>
  void vector(std::vector<T, Allocator>& v) {
    static_assert(stored_as_bytes<T>, "StateReader reads only types that are their bytes");
    const auto n = value<std::uint64_t>();
    // Checked against what is left before allocating: a damaged count cannot ask for terabytes.
    if (n > remaining() / (sizeof(T) > 0 ? sizeof(T) : 1)) fail("an array of " + std::to_string(n) + " entries");
    v.resize(std::size_t(n));
    if (n > 0) std::memcpy(static_cast<void*>(v.data()), take(std::size_t(n) * sizeof(T)), std::size_t(n) * sizeof(T));
  }
  void vector(std::vector<bool>& v);
  template <class T>
  void optional(std::optional<T>& v) {
    if (value<std::uint8_t>() != 0) {
      T x{};
      value(x);
      v = x;
    } else {
      v.reset();
    }
  }
  [[nodiscard]] std::string string();
  /// Throws unless the next marker is `name`.
  void tag(std::string_view name);
  /// Throws unless every byte was read.
  void finish() const;

  [[nodiscard]] std::size_t remaining() const noexcept { return in_.size() - position_; }
  [[noreturn]] void fail(const std::string& what_was_expected) const;

 private:
  const char* take(std::size_t n);
  std::string_view in_;
  std::size_t position_ = 0;
  std::string what_;
};

}  // namespace dfc
