#pragma once
// Reading JSON text from outside the program (scenario files, protocol headers,
// configure sections) with limits, and writing it back readably.
//
// nlohmann::json copies, compares, dumps and destroys values recursively, so a
// document nested a few hundred thousand levels deep overflows the stack long
// before any size limit is reached. parse_json_text() refuses such input while
// parsing (the parser itself keeps its own stack), so no deep value is ever
// built. It can also refuse duplicate object keys, which nlohmann otherwise
// resolves silently by keeping the last one.
#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "dfc/common/errors.hpp"

namespace dfc {

/// Deepest nesting of objects and arrays accepted in any JSON we read: ample
/// for scenarios and protocol messages (under 10 levels), far below the depth
/// at which recursive copies exhaust the stack.
inline constexpr std::size_t kMaxJsonNesting = 64;

struct JsonTextLimits {
  std::size_t max_nesting = kMaxJsonNesting;
  bool reject_duplicate_keys = false;
};

/// Why JSON text was refused. `key_path()` is the dotted path where the
/// problem was found ("" for the top level); `kind()` lets callers tell bad
/// syntax from well-formed text that breaks a limit.
class JsonTextError : public UserError {
 public:
  enum class Kind { syntax, too_deep, duplicate_key, number_out_of_range };
  JsonTextError(Kind kind, std::string key_path, std::string reason);
  [[nodiscard]] Kind kind() const noexcept { return kind_; }
  [[nodiscard]] const std::string& key_path() const noexcept { return key_path_; }
  [[nodiscard]] const std::string& reason() const noexcept { return reason_; }

 private:
  Kind kind_;
  std::string key_path_;
  std::string reason_;
};

/// Parses `text`; throws JsonTextError for bad syntax, nesting deeper than
/// `limits.max_nesting`, a number beyond the range of a double (1e999), or,
/// when asked, a key given twice in one object.
[[nodiscard]] nlohmann::json parse_json_text(std::string_view text, JsonTextLimits limits = {});

/// `value` as indented text when that stays small, else compact. Indentation
/// costs up to two bytes per nesting level on every line, so the indented form
/// of a large or deep document can be a hundred times its compact size; this
/// keeps what we write within a fixed multiple of the compact form.
[[nodiscard]] std::string readable_json(const nlohmann::json& value);

}  // namespace dfc
