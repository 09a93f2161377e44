#pragma once
// Declarations of scenario parameters: each key of each section is declared
// once (name, type, default, bounds, unit, one-line doc, upscaling rule), and
// that one declaration serves
//   - the parser (ConfigReader attached to a SectionDeclaration takes the
//     default, bounds and choices from it; a parser that reads a key the
//     declaration lacks is a bug, reported as std::logic_error),
//   - the generated --help text (describe_section),
//   - the published JSON Schema of the scenario (json_schema.hpp).
//
//   const SectionDeclaration& mesh = ...;      // static storage
//   ConfigReader cfg(object, "mesh", mesh);
//   double z0 = cfg.number("z_bottom_m");      // default and bounds from the declaration
//
// Declarations are static data (functions returning references to statics),
// so a section may point at its child sections.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace dfc {

/// Closed interval [min, max] for numeric settings; either end may be open-ended.
struct Bounds {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;  ///< true: the value must be > min rather than >= min
};

/// Bounds of a number that must be > 0.
inline constexpr Bounds kPositive{0.0, std::numeric_limits<double>::infinity(), true};

struct SectionDeclaration;

enum class ValueType {
  number,        ///< finite double
  integer,       ///< int64
  boolean,
  string,        ///< free text, or one of `choices`
  vector3,       ///< [x, y, z] of finite numbers (each within bounds)
  numbers,       ///< array of numbers (each within bounds)
  integers3,     ///< [i, j, k] of integers (each within the integer bounds)
  strings,       ///< array of strings
  object,        ///< a nested section (`section`), or any object when `section` is null
  objects,       ///< an array of `section` objects
  any,           ///< any JSON value; the parser checks it (e.g. a number or an array)
};

/// Whether a key must be given, has a declared default, or may be absent with
/// a meaning the parser computes (stated in `absent_means`).
enum class Presence { required, defaulted, optional };

struct ParameterDeclaration {
  std::string key;
  ValueType type = ValueType::number;
  std::string unit;  ///< SI unit of a number ("m", "Pa", "kg/m3"), "-" dimensionless, "" for other types
  std::string doc;   ///< one line
  Presence presence = Presence::required;
  nlohmann::json default_value;  ///< when presence == defaulted
  std::string absent_means;      ///< when presence == optional: what applies without the key
  Bounds bounds;                 ///< numbers and their arrays
  std::int64_t integer_min = std::numeric_limits<std::int64_t>::min();
  std::int64_t integer_max = std::numeric_limits<std::int64_t>::max();
  std::vector<std::string> choices;  ///< strings: the allowed values (empty: any)
  std::string upscaling;             ///< how particle upscaling by S changes it, where it applies
  double upscaling_exponent = 0.0;   ///< value * S^exponent under upscaling (laws)
  const SectionDeclaration* section = nullptr;  ///< object / objects

  // Builders: ParameterDeclaration::number("radius_m", "m", "pile radius").positive()
  static ParameterDeclaration number(std::string key, std::string unit, std::string doc);
  static ParameterDeclaration integer(std::string key, std::string doc);
  static ParameterDeclaration boolean(std::string key, std::string doc);
  static ParameterDeclaration string(std::string key, std::string doc);
  static ParameterDeclaration vector3(std::string key, std::string unit, std::string doc);
  static ParameterDeclaration numbers(std::string key, std::string unit, std::string doc);
  static ParameterDeclaration integers3(std::string key, std::string doc);
  static ParameterDeclaration strings(std::string key, std::string doc);
  static ParameterDeclaration object(std::string key, const SectionDeclaration& section);
  /// An object of free form (e.g. a server's configuration checked by the server).
  static ParameterDeclaration any_object(std::string key, std::string doc);
  static ParameterDeclaration objects(std::string key, const SectionDeclaration& section);
  static ParameterDeclaration any(std::string key, std::string doc);

  [[nodiscard]] ParameterDeclaration fallback(nlohmann::json value) const;
  /// Optional without a fixed default; `meaning` says what applies without it.
  [[nodiscard]] ParameterDeclaration optional(std::string meaning) const;
  [[nodiscard]] ParameterDeclaration within(Bounds value_bounds) const;
  [[nodiscard]] ParameterDeclaration positive() const { return within(kPositive); }
  [[nodiscard]] ParameterDeclaration at_least(double min) const { return within(Bounds{min}); }
  [[nodiscard]] ParameterDeclaration integer_within(std::int64_t min, std::int64_t max = std::numeric_limits<std::int64_t>::max()) const;
  [[nodiscard]] ParameterDeclaration one_of(std::vector<std::string> allowed) const;
  [[nodiscard]] ParameterDeclaration upscaled(std::string rule, double exponent = 0.0) const;
};

/// One value of a section's selector key ("type": "box") and the keys it adds.
struct SectionVariant {
  std::string value{};
  std::string doc{};
  const SectionDeclaration* keys = nullptr;  ///< the keys this variant adds (may be null: none)
};

/// The declaration of one JSON object of a scenario.
struct SectionDeclaration {
  std::string name{};  ///< for messages and the schema's $defs, e.g. "fdm.mesh"
  std::string doc{};
  std::vector<ParameterDeclaration> parameters{};
  /// Key whose value picks one of `variants` ("type", "law", "model"); empty: none.
  /// The selector itself is declared in `parameters` (its choices are the variants' values).
  std::string selector{};
  std::vector<SectionVariant> variants{};

  [[nodiscard]] const ParameterDeclaration* find(std::string_view key) const noexcept;
  [[nodiscard]] const SectionVariant* find_variant(std::string_view value) const noexcept;
};

/// "a number in [0, 1]", "a positive number", ...: what `bounds` allow, for messages.
[[nodiscard]] std::string describe_bounds(Bounds bounds);
/// The default or absent meaning of a declared key, for --help: "default 0.8", "required", "default: top of the mesh".
[[nodiscard]] std::string describe_presence(const ParameterDeclaration& parameter);
/// --help text of a section: one line per key (type, unit, bounds, default, doc),
/// nested sections and variants indented below their key.
[[nodiscard]] std::string describe_section(const SectionDeclaration& section, int indent = 2);

}  // namespace dfc
