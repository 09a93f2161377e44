#include "dfc/common/json_text.hpp"

#include <algorithm>
#include <set>
#include <vector>

#include "dfc/common/echo.hpp"

namespace dfc {

namespace {

/// Tracks where the parser is, from its callback events, so that every refusal
/// can name the key path ("gravity.g_level", "variants[2].patch").
class ParsePosition {
 public:
  void enter(bool is_object) { levels_.push_back(Level{is_object, {}, {}, 0}); }
  [[nodiscard]] std::size_t depth() const noexcept { return levels_.size(); }

  /// Records the key just read; false if this object already had it.
  bool key(std::string key) {
    Level& level = levels_.back();
    level.key = std::move(key);
    return level.seen_keys.insert(level.key).second;
  }

  /// A value (scalar, or a container that just closed) is complete.
  void value_done() {
    if (!levels_.empty() && !levels_.back().is_object) ++levels_.back().index;
  }

  void leave() {
    levels_.pop_back();
    value_done();
  }

  [[nodiscard]] std::string path() const {
    std::string text;
    for (const Level& level : levels_) {
      if (!level.is_object) text += "[" + std::to_string(level.index) + "]";
      else if (!level.key.empty()) text += (text.empty() ? "" : ".") + echoed(level.key);
    }
    return text;
  }

 private:
  struct Level {
    bool is_object;
    std::string key;                 // the object key being read (objects)
    std::set<std::string> seen_keys;  // every key of this object so far (objects)
    std::size_t index;               // the element being read (arrays)
  };
  std::vector<Level> levels_;
};

/// The deepest nesting of objects and arrays in `text`, counted from the
/// brackets outside strings without building anything. Exact for valid JSON;
/// for anything else the result does not matter, as the plain parser refuses
/// it and the checking parser then reports where.
std::size_t nesting_depth(std::string_view text) {
  std::size_t depth = 0;
  std::size_t deepest = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;  // the escaped character cannot end the string
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == '}' || c == ']') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

/// nlohmann's messages start with "[json.exception.<kind>.<id>] ".
std::string without_exception_tag(const char* message) {
  const std::string text = message;
  const auto end = text.find("] ");
  return end == std::string::npos ? text : text.substr(end + 2);
}

}  // namespace

JsonTextError::JsonTextError(Kind kind, std::string key_path, std::string reason)
    : UserError((key_path.empty() ? std::string() : key_path + ": ") + reason), kind_(kind), key_path_(std::move(key_path)), reason_(std::move(reason)) {}

nlohmann::json parse_json_text(std::string_view text, JsonTextLimits limits) {
  // Fast path for every protocol header (two or more per exchange): nlohmann's
  // parser with a callback per event takes ~1.5x as long as without, and only
  // the duplicate-key check needs the events. A depth within the limit,
  // measured first, keeps the guarantee that no deep value is ever built.
  if (!limits.reject_duplicate_keys && nesting_depth(text) <= limits.max_nesting) {
    try {
      return nlohmann::json::parse(text.begin(), text.end());
    } catch (const nlohmann::json::exception&) {
      // Refused: the checking parser below refuses it too and says where.
    }
  }
  using Event = nlohmann::json::parse_event_t;
  ParsePosition position;
  // The callback runs before each container is built, so throwing here stops
  // a deep document before any deep value exists.
  const auto on_event = [&](int /*depth*/, Event event, nlohmann::json& parsed) {
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        if (position.depth() >= limits.max_nesting)
          throw JsonTextError(JsonTextError::Kind::too_deep, position.path(),
                              "objects and arrays nested more than " + std::to_string(limits.max_nesting) +
                                  " levels deep; flatten this value (nothing we read needs that depth)");
        position.enter(event == Event::object_start);
        break;
      case Event::key:
        if (!position.key(parsed.get<std::string>()) && limits.reject_duplicate_keys)
          throw JsonTextError(JsonTextError::Kind::duplicate_key, position.path(),
                              "key given twice in the same object; keep only one (JSON readers disagree on which one wins)");
        break;
      case Event::object_end:
      case Event::array_end:
        position.leave();
        break;
      case Event::value:
        position.value_done();
        break;
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text.begin(), text.end(), on_event);
  } catch (const nlohmann::json::out_of_range& e) {
    // 1e999 and the like: nlohmann refuses numbers a double cannot hold.
    throw JsonTextError(JsonTextError::Kind::number_out_of_range, position.path(),
                        without_exception_tag(e.what()) + "; numbers must lie within ±1.8e308 (a double)");
  } catch (const nlohmann::json::parse_error& e) {
    throw JsonTextError(JsonTextError::Kind::syntax, position.path(), without_exception_tag(e.what()));
  }
}

std::string readable_json(const nlohmann::json& value) {
  // Up to ~130x growth at kMaxJsonNesting levels: 256 KiB of compact text stays
  // within tens of MiB indented; anything larger is written compact.
  constexpr std::size_t kLargestIndentedJson = 256 * 1024;
  std::string compact = value.dump();
  if (compact.size() > kLargestIndentedJson) return compact;
  return value.dump(2);
}

}  // namespace dfc
