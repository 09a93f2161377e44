#pragma once
// Shared parameter files in scenarios: an object that holds
//
//   "include": "materials/soft_rock_softbond.json"
//
// is that file's object (a path relative to the file that names it) with the
// object's other keys applied on top as a JSON Merge Patch (RFC 7386, as
// variants are). One calibrated parameter set then serves every scenario that
// names it, instead of copies that drift apart. Included files may include
// others; the scenario the coupler writes to the results holds the expanded
// document, so a run stays self-contained.
#include <filesystem>
#include <functional>

#include <nlohmann/json.hpp>

namespace dfc::coupler {

/// Reads and parses one JSON file (the scenario's own rules: size, syntax,
/// duplicate keys).
using JsonFileLoader = std::function<nlohmann::json(const std::filesystem::path&)>;

/// `document` (read from a file in `directory`) with every "include" resolved.
/// Throws dfc::ConfigError naming the key path of an "include" that is not a
/// string, names a file that is not a JSON object, or nests deeper than 8
/// files (a cycle).
[[nodiscard]] nlohmann::json resolve_includes(const nlohmann::json& document, const std::filesystem::path& directory, const JsonFileLoader& load);

}  // namespace dfc::coupler
