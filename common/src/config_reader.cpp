#include "dfc/common/config_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "dfc/common/echo.hpp"

namespace dfc {

namespace {

std::string type_name(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::boolean: return "a boolean";
    case nlohmann::json::value_t::string: return "a string";
    case nlohmann::json::value_t::array: return "an array";
    case nlohmann::json::value_t::object: return "an object";
    default: return "a number";
  }
}

std::string short_dump(const nlohmann::json& value) { return echoed(value.dump()); }

std::string format_number(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

// Levenshtein distance, for "did you mean" suggestions on unknown keys.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

ConfigReader::ConfigReader(const nlohmann::json& object, std::string path) : object_(&object), path_(std::move(path)) {
  if (!object.is_object()) throw ConfigError(path_, "expected an object ({...}), got " + type_name(object));
}

ConfigReader::ConfigReader(const nlohmann::json& object, std::string path, const SectionDeclaration& declaration)
    : ConfigReader(object, std::move(path)) {
  declaration_ = &declaration;
}

ConfigReader ConfigReader::declared_as_section(const SectionDeclaration& declaration) const {
  return ConfigReader(*object_, path_, declaration);
}

std::string ConfigReader::key_path(std::string_view key) const {
  return path_.empty() ? echoed(key) : path_ + "." + echoed(key);
}

const ParameterDeclaration* ConfigReader::declared(std::string_view key) const {
  if (declaration_ == nullptr) return nullptr;
  if (const ParameterDeclaration* p = declaration_->find(key)) return p;
  if (variant_keys_ != nullptr)
    if (const ParameterDeclaration* p = variant_keys_->find(key)) return p;
  throw std::logic_error("the parser reads \"" + key_path(key) + "\", which the declaration of section \"" + declaration_->name +
                         "\" lacks: declare it there (dfc/common/declaration.hpp)");
}

const ParameterDeclaration& ConfigReader::declared_as(std::string_view key, ValueType type) const {
  const ParameterDeclaration* p = declared(key);
  if (p->type != type && p->type != ValueType::any)
    throw std::logic_error("the parser reads \"" + key_path(key) + "\" as another type than section \"" + declaration_->name + "\" declares");
  return *p;
}

const nlohmann::json* ConfigReader::declared_value(const ParameterDeclaration& parameter) {
  const nlohmann::json* value = find(parameter.key);
  if (value != nullptr) return value;
  switch (parameter.presence) {
    case Presence::defaulted: return &parameter.default_value;
    // An optional key the parser reads is needed here (it tests has() where
    // the key may be absent): missing, as a required one.
    case Presence::required:
    case Presence::optional: break;
  }
  fail(parameter.key, "missing required key (" + parameter.doc + ")");
}

void ConfigReader::undeclared_call(std::string_view key, std::string_view call) const {
  if (declaration_ != nullptr)
    throw std::logic_error("the parser gives " + std::string(call) + " for \"" + key_path(key) + "\", whose section \"" +
                           declaration_->name + "\" is declared: the declaration holds them; read the key by name only");
}

bool ConfigReader::has(std::string_view key) const {
  (void)declared(key);
  const auto it = object_->find(std::string(key));
  return it != object_->end() && !it->is_null();
}

void ConfigReader::fail(std::string_view key, const std::string& reason) const { throw ConfigError(key_path(key), reason); }

const nlohmann::json* ConfigReader::find(std::string_view key) {
  known_.emplace(key);
  const auto it = object_->find(std::string(key));
  if (it == object_->end() || it->is_null()) return nullptr;
  return &*it;
}

const nlohmann::json& ConfigReader::require(std::string_view key, std::string_view expected) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) fail(key, "missing required key; expected " + std::string(expected));
  return *value;
}

double ConfigReader::checked_number(std::string_view key, const nlohmann::json& value, Bounds bounds) const {
  if (!value.is_number()) fail(key, "expected " + describe_bounds(bounds) + ", got " + type_name(value) + " " + short_dump(value));
  const double x = value.get<double>();
  const bool below = bounds.min_exclusive ? !(x > bounds.min) : !(x >= bounds.min);
  if (!std::isfinite(x) || below || !(x <= bounds.max))
    fail(key, "expected " + describe_bounds(bounds) + ", got " + format_number(x));
  return x;
}

namespace {
bool unbounded(Bounds b) { return !std::isfinite(b.min) && !std::isfinite(b.max); }
}  // namespace

double ConfigReader::number(std::string_view key, Bounds bounds) {
  if (declaration_ != nullptr) {
    if (!unbounded(bounds)) undeclared_call(key, "bounds");
    const ParameterDeclaration& p = declared_as(key, ValueType::number);
    const nlohmann::json* value = declared_value(p);
    return checked_number(key, *value, p.bounds);
  }
  return checked_number(key, require(key, describe_bounds(bounds)), bounds);
}

double ConfigReader::number(std::string_view key, double fallback, Bounds bounds) {
  undeclared_call(key, "a default");
  const nlohmann::json* value = find(key);
  return value == nullptr ? fallback : checked_number(key, *value, bounds);
}

double ConfigReader::positive(std::string_view key) {
  undeclared_call(key, "bounds (positive)");
  return number(key, kPositive);
}

double ConfigReader::positive(std::string_view key, double fallback) { return number(key, fallback, kPositive); }

std::int64_t ConfigReader::integer(std::string_view key, std::int64_t min_value) {
  if (declaration_ != nullptr) {
    if (min_value != std::numeric_limits<std::int64_t>::min()) undeclared_call(key, "a lower bound");
    const ParameterDeclaration& p = declared_as(key, ValueType::integer);
    const nlohmann::json* value = declared_value(p);
    return checked_integer(key, *value, p.integer_min, p.integer_max);
  }
  return integer_in(key, min_value, std::numeric_limits<std::int64_t>::max());
}

std::int64_t ConfigReader::integer(std::string_view key, std::int64_t fallback, std::int64_t min_value) {
  undeclared_call(key, "a default");
  return has(key) ? integer(key, min_value) : (accept(key), fallback);
}

std::int64_t ConfigReader::integer(std::string_view key, std::int64_t fallback, std::int64_t min_value, std::int64_t max_value) {
  undeclared_call(key, "a default");
  return has(key) ? integer_in(key, min_value, max_value) : (accept(key), fallback);
}

std::int64_t ConfigReader::integer_in(std::string_view key, std::int64_t min_value, std::int64_t max_value) {
  const bool bounded = max_value != std::numeric_limits<std::int64_t>::max();
  const std::string expected = bounded ? "an integer in [" + std::to_string(min_value) + ", " + std::to_string(max_value) + "]"
                                       : "an integer >= " + std::to_string(min_value);
  return checked_integer(key, require(key, expected), min_value, max_value);
}

std::int64_t ConfigReader::checked_integer(std::string_view key, const nlohmann::json& value, std::int64_t min_value,
                                           std::int64_t max_value) const {
  const bool has_min = min_value != std::numeric_limits<std::int64_t>::min();
  const bool has_max = max_value != std::numeric_limits<std::int64_t>::max();
  const std::string expected = has_min && has_max ? "an integer in [" + std::to_string(min_value) + ", " + std::to_string(max_value) + "]"
                               : has_min          ? "an integer >= " + std::to_string(min_value)
                               : has_max          ? "an integer <= " + std::to_string(max_value)
                                                  : "an integer";
  if (!value.is_number_integer()) fail(key, "expected an integer, got " + type_name(value) + " " + short_dump(value));
  // Unsigned values beyond int64 (e.g. 2^64 - 1) must not wrap to a small number.
  if (value.is_number_unsigned() && value.get<std::uint64_t>() > std::uint64_t(std::numeric_limits<std::int64_t>::max()))
    fail(key, "expected " + expected + ", got " + value.dump());
  const auto x = value.get<std::int64_t>();
  if (x < min_value || x > max_value) fail(key, "expected " + expected + ", got " + value.dump());
  return x;
}

std::array<double, 3> ConfigReader::vec3(std::string_view key) {
  Bounds bounds;
  const nlohmann::json* given = nullptr;
  if (declaration_ != nullptr) {
    const ParameterDeclaration& p = declared_as(key, ValueType::vector3);
    bounds = p.bounds;
    given = declared_value(p);
  } else {
    given = &require(key, "an array of 3 numbers");
  }
  const nlohmann::json& value = *given;
  if (!value.is_array() || value.size() != 3 || !std::all_of(value.begin(), value.end(), [](const auto& v) { return v.is_number(); }))
    fail(key, "expected an array of 3 numbers [x, y, z], got " + short_dump(value));
  std::array<double, 3> out{};
  for (std::size_t i = 0; i < 3; ++i) {
    out[i] = value[i].get<double>();
    if (!std::isfinite(out[i])) fail(key, "expected finite numbers, got " + short_dump(value));
    if (!unbounded(bounds)) out[i] = checked_number(std::string(key) + "[" + std::to_string(i) + "]", value[i], bounds);
  }
  return out;
}

std::array<double, 3> ConfigReader::vec3(std::string_view key, std::array<double, 3> fallback) {
  undeclared_call(key, "a default");
  return has(key) ? vec3(key) : (accept(key), fallback);
}

std::vector<double> ConfigReader::numbers(std::string_view key, Bounds bounds) {
  const nlohmann::json* given = nullptr;
  if (declaration_ != nullptr) {
    if (!unbounded(bounds)) undeclared_call(key, "bounds");
    const ParameterDeclaration& p = declared_as(key, ValueType::numbers);
    bounds = p.bounds;
    given = declared_value(p);
  } else {
    given = &require(key, "an array of numbers");
  }
  const nlohmann::json& value = *given;
  if (!value.is_array()) fail(key, "expected an array of numbers, got " + type_name(value));
  std::vector<double> out;
  out.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i)
    out.push_back(checked_number(std::string(key) + "[" + std::to_string(i) + "]", value[i], bounds));
  return out;
}

std::array<std::int64_t, 3> ConfigReader::integers3(std::string_view key) {
  if (declaration_ == nullptr) throw std::logic_error("integers3(\"" + key_path(key) + "\") needs a declared reader");
  const ParameterDeclaration& p = declared_as(key, ValueType::integers3);
  const nlohmann::json* given = declared_value(p);
  const nlohmann::json& value = *given;
  if (!value.is_array() || value.size() != 3) fail(key, "expected an array of 3 integers [i, j, k], got " + short_dump(value));
  std::array<std::int64_t, 3> out{};
  for (std::size_t i = 0; i < 3; ++i)
    out[i] = checked_integer(std::string(key) + "[" + std::to_string(i) + "]", value[i], p.integer_min, p.integer_max);
  return out;
}

bool ConfigReader::boolean(std::string_view key) {
  const nlohmann::json* given = nullptr;
  if (declaration_ != nullptr) {
    given = declared_value(declared_as(key, ValueType::boolean));
  } else {
    given = &require(key, "true or false");
  }
  if (!given->is_boolean()) fail(key, "expected true or false, got " + type_name(*given) + " " + short_dump(*given));
  return given->get<bool>();
}

bool ConfigReader::boolean(std::string_view key, bool fallback) {
  undeclared_call(key, "a default");
  return has(key) ? boolean(key) : (accept(key), fallback);
}

std::string ConfigReader::string(std::string_view key) {
  const nlohmann::json* given = nullptr;
  const ParameterDeclaration* p = nullptr;
  if (declaration_ != nullptr) {
    p = &declared_as(key, ValueType::string);
    given = declared_value(*p);
  } else {
    given = &require(key, "a string");
  }
  if (!given->is_string()) fail(key, "expected a string, got " + type_name(*given) + " " + short_dump(*given));
  std::string value = given->get<std::string>();
  if (p != nullptr) require_choice(key, value, p->choices);
  if (p != nullptr && key == declaration_->selector)
    if (const SectionVariant* variant = declaration_->find_variant(value)) variant_keys_ = variant->keys;
  return value;
}

std::string ConfigReader::string(std::string_view key, std::string fallback) {
  undeclared_call(key, "a default");
  return has(key) ? string(key) : (accept(key), std::move(fallback));
}

std::string ConfigReader::choice(std::string_view key, const std::vector<std::string>& allowed) {
  undeclared_call(key, "the choices");
  std::string value = string(key);
  require_choice(key, value, allowed);
  return value;
}

std::string ConfigReader::choice(std::string_view key, const std::vector<std::string>& allowed, std::string fallback) {
  undeclared_call(key, "a default");
  return has(key) ? choice(key, allowed) : (accept(key), std::move(fallback));
}

std::vector<std::string> ConfigReader::strings(std::string_view key) {
  const nlohmann::json* given = nullptr;
  const ParameterDeclaration* p = nullptr;
  if (declaration_ != nullptr) {
    p = &declared_as(key, ValueType::strings);
    given = declared_value(*p);
  } else {
    given = &require(key, "an array of strings");
  }
  const nlohmann::json& value = *given;
  if (!value.is_array() || !std::all_of(value.begin(), value.end(), [](const auto& v) { return v.is_string(); }))
    fail(key, "expected an array of strings, got " + short_dump(value));
  auto entries = value.get<std::vector<std::string>>();
  // Declared choices hold for every entry; a wrong one is named by its place.
  if (p != nullptr)
    for (std::size_t k = 0; k < entries.size(); ++k) require_choice(std::string(key) + "[" + std::to_string(k) + "]", entries[k], p->choices);
  return entries;
}

void ConfigReader::require_choice(std::string_view key, const std::string& value, const std::vector<std::string>& allowed) const {
  if (allowed.empty() || std::find(allowed.begin(), allowed.end(), value) != allowed.end()) return;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "\"" : ", \"") + a + "\"";
  fail(key, "unknown value \"" + echoed(value) + "\"; expected one of " + list);
}

ConfigReader ConfigReader::nested(const nlohmann::json& value, std::string path, const ParameterDeclaration* parameter) const {
  if (parameter != nullptr && parameter->section != nullptr) return ConfigReader(value, std::move(path), *parameter->section);
  return ConfigReader(value, std::move(path));
}

ConfigReader ConfigReader::child(std::string_view key) {
  const ParameterDeclaration* p = declaration_ != nullptr ? &declared_as(key, ValueType::object) : nullptr;
  const nlohmann::json& value = require(key, "an object");
  if (!value.is_object()) fail(key, "expected an object ({...}), got " + type_name(value));
  return nested(value, key_path(key), p);
}

std::optional<ConfigReader> ConfigReader::optional_child(std::string_view key) {
  const ParameterDeclaration* p = declaration_ != nullptr ? &declared_as(key, ValueType::object) : nullptr;
  const nlohmann::json* value = find(key);
  if (value == nullptr) return std::nullopt;
  if (!value->is_object()) fail(key, "expected an object ({...}), got " + type_name(*value));
  return nested(*value, key_path(key), p);
}

std::vector<ConfigReader> ConfigReader::children(std::string_view key) {
  const ParameterDeclaration* p = declaration_ != nullptr ? &declared_as(key, ValueType::objects) : nullptr;
  const nlohmann::json& value = require(key, "an array of objects");
  if (!value.is_array()) fail(key, "expected an array of objects, got " + type_name(value));
  std::vector<ConfigReader> out;
  for (std::size_t i = 0; i < value.size(); ++i) out.push_back(nested(value[i], key_path(key) + "[" + std::to_string(i) + "]", p));
  return out;
}

const nlohmann::json& ConfigReader::raw(std::string_view key) {
  (void)declared(key);
  return require(key, "a value");
}

void ConfigReader::accept(std::string_view key) {
  (void)declared(key);
  known_.emplace(key);
}

void ConfigReader::finish() const {
  for (const auto& [key, value] : object_->items()) {
    if (known_.count(key) != 0 || key == "comment" || (!key.empty() && key[0] == '_')) continue;
    std::set<std::string, std::less<>> candidates = known_;
    for (const SectionDeclaration* section : {declaration_, variant_keys_})
      if (section != nullptr)
        for (const auto& p : section->parameters) candidates.insert(p.key);
    std::string best;
    std::size_t best_distance = 3;  // suggest only close matches
    for (const auto& candidate : candidates) {
      const std::size_t d = edit_distance(key, candidate);
      if (d < best_distance) best_distance = d, best = candidate;
    }
    std::string reason = "unknown key";
    if (!best.empty()) reason += "; did you mean \"" + best + "\"?";
    else if (!candidates.empty()) {
      reason += "; known keys here are:";
      for (const auto& candidate : candidates) reason += " " + candidate;
    }
    throw ConfigError(key_path(key), reason);
  }
}

ParameterDeclaration thread_count_declaration() {
  return ParameterDeclaration::integer("threads", "OpenMP threads; 0 = the OpenMP default (OMP_NUM_THREADS or all cores)")
      .integer_within(0, kMaxThreads)
      .fallback(0);
}

int read_thread_count(ConfigReader& section) {
  if (section.declaration() != nullptr) return int(section.integer("threads"));
  return int(section.integer("threads", 0, 0, kMaxThreads));
}

std::string canonical_json(const nlohmann::json& value) { return value.dump(); }

}  // namespace dfc
