#pragma once
// ConfigReader: typed, validated access to one JSON object of a scenario.
//
// Every accessor records the key as known; finish() then rejects any key that
// was never asked for, so a typo ("radus") is an error naming the key path and
// the closest known key instead of a silently ignored setting (CONTRIBUTING.md §6).
// Errors are ConfigError with the dotted key path and what was expected.
//
// A reader attached to a SectionDeclaration (declaration.hpp) takes each key's
// default, bounds and choices from the declaration: the call names the key
// only (cfg.number("friction")). Giving a default or bounds at the call as
// well, or reading a key the declaration lacks, is a bug in the parser and
// throws std::logic_error (the test python.scenario_schema runs every server
// section of every shipped scenario through its parser with
// `<server> --check-config`, so such a bug fails the suite).
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

#include "dfc/common/declaration.hpp"
#include "dfc/common/errors.hpp"

namespace dfc {

class ConfigReader {
 public:
  /// `object` must outlive the reader. `path` is the dotted path of `object`
  /// itself within the scenario ("" for the root).
  ConfigReader(const nlohmann::json& object, std::string path);
  /// A reader whose keys are declared in `declaration` (static storage).
  ConfigReader(const nlohmann::json& object, std::string path, const SectionDeclaration& declaration);

  /// A reader of the same object that follows `declaration` (static storage).
  [[nodiscard]] ConfigReader declared_as_section(const SectionDeclaration& declaration) const;
  /// The declaration this reader follows; nullptr for an undeclared reader.
  [[nodiscard]] const SectionDeclaration* declaration() const noexcept { return declaration_; }
  /// The declaration of `key` (in the section or the variant its selector chose);
  /// std::logic_error when the reader is declared and the key is not; nullptr when undeclared.
  [[nodiscard]] const ParameterDeclaration* declared(std::string_view key) const;

  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  /// The object this reader reads.
  [[nodiscard]] const nlohmann::json& object() const noexcept { return *object_; }
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
  /// Declared readers only: [i, j, k] of integers within the declared range.
  [[nodiscard]] std::array<std::int64_t, 3> integers3(std::string_view key);

  // Other scalars -----------------------------------------------------------
  [[nodiscard]] bool boolean(std::string_view key);
  [[nodiscard]] bool boolean(std::string_view key, bool fallback);
  [[nodiscard]] std::string string(std::string_view key);
  [[nodiscard]] std::string string(std::string_view key, std::string fallback);
  /// A string that must be one of `allowed`; the error lists them.
  [[nodiscard]] std::string choice(std::string_view key, const std::vector<std::string>& allowed);
  [[nodiscard]] std::string choice(std::string_view key, const std::vector<std::string>& allowed, std::string fallback);
  /// An array of strings; where the declaration gives choices (one_of), every
  /// entry must be one of them and the error names the entry ("contents[2]").
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
  std::int64_t checked_integer(std::string_view key, const nlohmann::json& value, std::int64_t min_value, std::int64_t max_value) const;
  double checked_number(std::string_view key, const nlohmann::json& value, Bounds bounds) const;
  // Throws ConfigError for `key` listing `allowed` when `value` is not one of them (none: any value).
  void require_choice(std::string_view key, const std::string& value, const std::vector<std::string>& allowed) const;
  // Declared readers: the declaration of `key`, checked to be of `type`.
  const ParameterDeclaration& declared_as(std::string_view key, ValueType type) const;
  // Declared readers: the value of `key`, its declared default when absent;
  // ConfigError for an absent required or optional key (never nullptr).
  const nlohmann::json* declared_value(const ParameterDeclaration& parameter);
  // Throws std::logic_error if this reader is declared: `call` gives a default
  // or bounds that belong in the declaration.
  void undeclared_call(std::string_view key, std::string_view call) const;
  ConfigReader nested(const nlohmann::json& value, std::string path, const ParameterDeclaration* parameter) const;

  const nlohmann::json* object_;
  std::string path_;
  const SectionDeclaration* declaration_ = nullptr;
  const SectionDeclaration* variant_keys_ = nullptr;  ///< keys added by the variant the selector chose
  std::set<std::string, std::less<>> known_;
};

/// Most threads a solver section may ask for: more than any machine we run on
/// has, few enough that the OpenMP runtime can create them.
inline constexpr std::int64_t kMaxThreads = 1024;

/// The declaration of the key "threads" of a solver section: 0 (the OpenMP default) to kMaxThreads.
[[nodiscard]] ParameterDeclaration thread_count_declaration();
/// The optional key "threads" of a solver section: 0 (the OpenMP default) to kMaxThreads.
[[nodiscard]] int read_thread_count(ConfigReader& section);

/// Canonical serialisation used for hashing (sorted keys, no whitespace).
[[nodiscard]] std::string canonical_json(const nlohmann::json& value);

}  // namespace dfc
