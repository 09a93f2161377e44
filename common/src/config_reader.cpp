#include "dfc/common/config_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

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

std::string short_dump(const nlohmann::json& value) {
  std::string text = value.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return text;
}

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

std::string ConfigReader::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

bool ConfigReader::has(std::string_view key) const {
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

double ConfigReader::number(std::string_view key, Bounds bounds) {
  return checked_number(key, require(key, describe_bounds(bounds)), bounds);
}

double ConfigReader::number(std::string_view key, double fallback, Bounds bounds) {
  const nlohmann::json* value = find(key);
  return value == nullptr ? fallback : checked_number(key, *value, bounds);
}

double ConfigReader::positive(std::string_view key) { return number(key, Bounds{0.0, std::numeric_limits<double>::infinity(), true}); }

double ConfigReader::positive(std::string_view key, double fallback) {
  return number(key, fallback, Bounds{0.0, std::numeric_limits<double>::infinity(), true});
}

std::int64_t ConfigReader::integer(std::string_view key, std::int64_t min_value) {
  return integer_in(key, min_value, std::numeric_limits<std::int64_t>::max());
}

std::int64_t ConfigReader::integer(std::string_view key, std::int64_t fallback, std::int64_t min_value) {
  return has(key) ? integer(key, min_value) : (accept(key), fallback);
}

std::int64_t ConfigReader::integer(std::string_view key, std::int64_t fallback, std::int64_t min_value, std::int64_t max_value) {
  return has(key) ? integer_in(key, min_value, max_value) : (accept(key), fallback);
}

std::int64_t ConfigReader::integer_in(std::string_view key, std::int64_t min_value, std::int64_t max_value) {
  const bool bounded = max_value != std::numeric_limits<std::int64_t>::max();
  const std::string expected = bounded ? "an integer in [" + std::to_string(min_value) + ", " + std::to_string(max_value) + "]"
                                       : "an integer >= " + std::to_string(min_value);
  const nlohmann::json& value = require(key, expected);
  if (!value.is_number_integer()) fail(key, "expected an integer, got " + type_name(value) + " " + short_dump(value));
  // Unsigned values beyond int64 (e.g. 2^64 - 1) must not wrap to a small number.
  if (value.is_number_unsigned() && value.get<std::uint64_t>() > std::uint64_t(std::numeric_limits<std::int64_t>::max()))
    fail(key, "expected " + expected + ", got " + value.dump());
  const auto x = value.get<std::int64_t>();
  if (x < min_value || x > max_value) fail(key, "expected " + expected + ", got " + value.dump());
  return x;
}

std::array<double, 3> ConfigReader::vec3(std::string_view key) {
  const nlohmann::json& value = require(key, "an array of 3 numbers");
  if (!value.is_array() || value.size() != 3 || !std::all_of(value.begin(), value.end(), [](const auto& v) { return v.is_number(); }))
    fail(key, "expected an array of 3 numbers [x, y, z], got " + short_dump(value));
  std::array<double, 3> out{};
  for (std::size_t i = 0; i < 3; ++i) {
    out[i] = value[i].get<double>();
    if (!std::isfinite(out[i])) fail(key, "expected finite numbers, got " + short_dump(value));
  }
  return out;
}

std::array<double, 3> ConfigReader::vec3(std::string_view key, std::array<double, 3> fallback) {
  return has(key) ? vec3(key) : (accept(key), fallback);
}

std::vector<double> ConfigReader::numbers(std::string_view key, Bounds bounds) {
  const nlohmann::json& value = require(key, "an array of numbers");
  if (!value.is_array()) fail(key, "expected an array of numbers, got " + type_name(value));
  std::vector<double> out;
  out.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i)
    out.push_back(checked_number(std::string(key) + "[" + std::to_string(i) + "]", value[i], bounds));
  return out;
}

bool ConfigReader::boolean(std::string_view key) {
  const nlohmann::json& value = require(key, "true or false");
  if (!value.is_boolean()) fail(key, "expected true or false, got " + type_name(value) + " " + short_dump(value));
  return value.get<bool>();
}

bool ConfigReader::boolean(std::string_view key, bool fallback) { return has(key) ? boolean(key) : (accept(key), fallback); }

std::string ConfigReader::string(std::string_view key) {
  const nlohmann::json& value = require(key, "a string");
  if (!value.is_string()) fail(key, "expected a string, got " + type_name(value) + " " + short_dump(value));
  return value.get<std::string>();
}

std::string ConfigReader::string(std::string_view key, std::string fallback) {
  return has(key) ? string(key) : (accept(key), std::move(fallback));
}

std::string ConfigReader::choice(std::string_view key, const std::vector<std::string>& allowed) {
  std::string value = string(key);
  if (std::find(allowed.begin(), allowed.end(), value) == allowed.end()) {
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "\"" : ", \"") + a + "\"";
    fail(key, "unknown value \"" + value + "\"; expected one of " + list);
  }
  return value;
}

std::string ConfigReader::choice(std::string_view key, const std::vector<std::string>& allowed, std::string fallback) {
  return has(key) ? choice(key, allowed) : (accept(key), std::move(fallback));
}

std::vector<std::string> ConfigReader::strings(std::string_view key) {
  const nlohmann::json& value = require(key, "an array of strings");
  if (!value.is_array() || !std::all_of(value.begin(), value.end(), [](const auto& v) { return v.is_string(); }))
    fail(key, "expected an array of strings, got " + short_dump(value));
  return value.get<std::vector<std::string>>();
}

ConfigReader ConfigReader::child(std::string_view key) {
  const nlohmann::json& value = require(key, "an object");
  if (!value.is_object()) fail(key, "expected an object ({...}), got " + type_name(value));
  return ConfigReader(value, key_path(key));
}

std::optional<ConfigReader> ConfigReader::optional_child(std::string_view key) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) return std::nullopt;
  if (!value->is_object()) fail(key, "expected an object ({...}), got " + type_name(*value));
  return ConfigReader(*value, key_path(key));
}

std::vector<ConfigReader> ConfigReader::children(std::string_view key) {
  const nlohmann::json& value = require(key, "an array of objects");
  if (!value.is_array()) fail(key, "expected an array of objects, got " + type_name(value));
  std::vector<ConfigReader> out;
  for (std::size_t i = 0; i < value.size(); ++i) out.emplace_back(value[i], key_path(key) + "[" + std::to_string(i) + "]");
  return out;
}

const nlohmann::json& ConfigReader::raw(std::string_view key) { return require(key, "a value"); }

void ConfigReader::accept(std::string_view key) { known_.emplace(key); }

void ConfigReader::finish() const {
  for (const auto& [key, value] : object_->items()) {
    if (known_.count(key) != 0 || key == "comment" || (!key.empty() && key[0] == '_')) continue;
    std::string best;
    std::size_t best_distance = 3;  // suggest only close matches
    for (const auto& candidate : known_) {
      const std::size_t d = edit_distance(key, candidate);
      if (d < best_distance) best_distance = d, best = candidate;
    }
    std::string reason = "unknown key";
    if (!best.empty()) reason += "; did you mean \"" + best + "\"?";
    else if (!known_.empty()) {
      reason += "; known keys here are:";
      for (const auto& candidate : known_) reason += " " + candidate;
    }
    throw ConfigError(key_path(key), reason);
  }
}

std::string describe_bounds(Bounds bounds) {
  const bool has_min = std::isfinite(bounds.min);
  const bool has_max = std::isfinite(bounds.max);
  if (has_min && bounds.min_exclusive && bounds.min == 0.0 && !has_max) return "a positive number";
  if (has_min && has_max)
    return "a number in " + std::string(bounds.min_exclusive ? "(" : "[") + format_number(bounds.min) + ", " +
           format_number(bounds.max) + "]";
  if (has_min) return "a number " + std::string(bounds.min_exclusive ? "> " : ">= ") + format_number(bounds.min);
  if (has_max) return "a number <= " + format_number(bounds.max);
  return "a finite number";
}

int read_thread_count(ConfigReader& section) { return int(section.integer("threads", 0, 0, kMaxThreads)); }

std::string canonical_json(const nlohmann::json& value) { return value.dump(); }

}  // namespace dfc
