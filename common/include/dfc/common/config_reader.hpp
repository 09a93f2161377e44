#pragma once
// ConfigReader: typed, validated access to one JSON object of a scenario.
//
// Every accessor records the key as known; finish() then rejects any key that
// was never asked for, so a typo ("radus") is an error naming the key path and
// the closest known key instead of a silently ignored setting (CONTRIBUTING.md §6).
// Errors are ConfigError with the dotted key path and what was expected.
//
//   ConfigReader cfg(section, "dem");
//   const double r = cfg.positive("radius_m");            // required, > 0
//   const double mu = cfg.number("friction", 0.5, {0, 10}); // optional, in [0, 10]
//   auto law = cfg.choice("law", {"linear"});
//   ConfigReader walls = cfg.child("walls");  walls.finish();
//   cfg.finish();
#include <array>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "dfc/common/errors.hpp"

namespace dfc {

/// Closed interval [min, max] for numeric settings; either end may be open-ended.
struct Bounds {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;  ///< true: the value must be > min rather than >= min
};

class ConfigReader {
 public:
  /// `object` must outlive the reader. `path` is the dotted path of `object`
  /// itself within the scenario ("" for the root).
  ConfigReader(const nlohmann::json& object, std::string path);

  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  /// Dotted path of `key` inside this object.
  [[nodiscard]] std::string key_path(std::string_view key) const;
  [[nodiscard]] bool has(std::string_view key) const;
  /// Throws ConfigError for `key` with `reason`.
  [[noreturn]] void fail(std::string_view key, const std::string& reason) const;

  // Numbers -----------------------------------------------------------------
  [[nodiscard]] double number(std::string_view key, Bounds bounds = {});
  [[nodiscard]] double number(std::string_view key, double fallback, Bounds bounds = {});
  /// Required number > 0.
  [[nodiscard]] double positive(std::string_view key);
  [[nodiscard]] double positive(std::string_view key, double fallback);
  [[nodiscard]] std::int64_t integer(std::string_view key, std::int64_t min_value = std::numeric_limits<std::int64_t>::min());
  [[nodiscard]] std::int64_t integer(std::string_view key, std::int64_t fallback, std::int64_t min_value);
  /// Optional integer in [min_value, max_value].
  [[nodiscard]] std::int64_t integer(std::string_view key, std::int64_t fallback, std::int64_t min_value, std::int64_t max_value);
  [[nodiscard]] std::array<double, 3> vec3(std::string_view key);
  [[nodiscard]] std::array<double, 3> vec3(std::string_view key, std::array<double, 3> fallback);
  [[nodiscard]] std::vector<double> numbers(std::string_view key, Bounds bounds = {});

  // Other scalars -----------------------------------------------------------
  [[nodiscard]] bool boolean(std::string_view key);
  [[nodiscard]] bool boolean(std::string_view key, bool fallback);
  [[nodiscard]] std::string string(std::string_view key);
  [[nodiscard]] std::string string(std::string_view key, std::string fallback);
  /// A string that must be one of `allowed`; the error lists them.
  [[nodiscard]] std::string choice(std::string_view key, const std::vector<std::string>& allowed);
  [[nodiscard]] std::string choice(std::string_view key, const std::vector<std::string>& allowed, std::string fallback);
  [[nodiscard]] std::vector<std::string> strings(std::string_view key);

  // Nested objects ----------------------------------------------------------
  /// Required nested object. Call finish() on it too.
  [[nodiscard]] ConfigReader child(std::string_view key);
  /// Nested object if present (and not null).
  [[nodiscard]] std::optional<ConfigReader> optional_child(std::string_view key);
  /// Required array of objects.
  [[nodiscard]] std::vector<ConfigReader> children(std::string_view key);
  /// The raw JSON value of a key (marks it known); throws if absent.
  [[nodiscard]] const nlohmann::json& raw(std::string_view key);
  /// Marks `key` as known without reading it (e.g. a comment field).
  void accept(std::string_view key);

  /// Throws ConfigError for the first key that no accessor asked for.
  /// Keys starting with '_' and the key "comment" are free-form notes and always allowed.
  void finish() const;

 private:
  const nlohmann::json* find(std::string_view key);
  const nlohmann::json& require(std::string_view key, std::string_view expected);
  std::int64_t integer_in(std::string_view key, std::int64_t min_value, std::int64_t max_value);
  double checked_number(std::string_view key, const nlohmann::json& value, Bounds bounds) const;

  const nlohmann::json* object_;
  std::string path_;
  std::set<std::string, std::less<>> known_;
};

/// "a number in [0, 1]", "a positive number", ...: what `bounds` allow, for messages.
[[nodiscard]] std::string describe_bounds(Bounds bounds);

/// Most threads a solver section may ask for: more than any machine we run on
/// has, few enough that the OpenMP runtime can create them.
inline constexpr std::int64_t kMaxThreads = 1024;

/// The optional key "threads" of a solver section: 0 (the OpenMP default) to kMaxThreads.
[[nodiscard]] int read_thread_count(ConfigReader& section);

/// Canonical serialisation used for hashing (sorted keys, no whitespace).
[[nodiscard]] std::string canonical_json(const nlohmann::json& value);

}  // namespace dfc
