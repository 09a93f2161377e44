#include "dfc/coupler/scenario_includes.hpp"

#include <string>

#include "dfc/common/echo.hpp"
#include "dfc/common/errors.hpp"

namespace dfc::coupler {

namespace {

namespace fs = std::filesystem;

/// Files included within files: more than this is a cycle, not a design.
constexpr int kMaxIncludeDepth = 8;

nlohmann::json resolve(const nlohmann::json& value, const fs::path& directory, const JsonFileLoader& load, const std::string& path, int depth) {
  if (value.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (std::size_t k = 0; k < value.size(); ++k) out.push_back(resolve(value[k], directory, load, path + "[" + std::to_string(k) + "]", depth));
    return out;
  }
  if (!value.is_object()) return value;
  const std::string prefix = path.empty() ? "" : path + ".";
  nlohmann::json out = nlohmann::json::object();
  if (const auto it = value.find("include"); it != value.end()) {
    const std::string key = prefix + "include";
    if (!it->is_string() || it->get<std::string>().empty())
      throw ConfigError(key, "expected the path of a JSON file (relative to this file) whose object this one extends");
    if (depth >= kMaxIncludeDepth)
      throw ConfigError(key, "includes nest deeper than " + std::to_string(kMaxIncludeDepth) + " files; check for a file that includes itself");
    const fs::path file = directory / it->get<std::string>();
    nlohmann::json included;
    try {
      included = load(file);
    } catch (const UserError& e) {
      throw ConfigError(key, "cannot use '" + echoed(file.string(), kMaxEchoedPathBytes) + "': " + e.what());
    }
    if (!included.is_object()) throw ConfigError(key, "'" + echoed(file.string(), kMaxEchoedPathBytes) + "' holds no JSON object; an included file is an object of keys");
    out = resolve(included, file.parent_path(), load, path, depth + 1);
  }
  // The keys beside the include patch what it gives (RFC 7386): a null removes
  // a key at any depth below. The patch keeps its nulls until it is applied:
  // merged level by level, a null nested in an object without an include of
  // its own (`"participants": {"dem": {"config": {"pile": null}}}`) would be
  // applied to that empty level and lost before reaching the included key.
  // Without an include the object is returned with its nulls, for the include
  // of an enclosing object to apply.
  nlohmann::json patch = nlohmann::json::object();
  for (const auto& [name, child] : value.items())
    if (name != "include") patch[name] = resolve(child, directory, load, prefix + name, depth);
  if (!value.contains("include")) return patch;
  out.merge_patch(patch);
  return out;
}

/// The nulls no include consumed say "not set": removed, as a merge onto
/// nothing removes them.
void drop_nulls(nlohmann::json& value) {
  if (value.is_array())
    for (auto& element : value) drop_nulls(element);
  if (!value.is_object()) return;
  for (auto it = value.begin(); it != value.end();) {
    if (it->is_null()) {
      it = value.erase(it);
    } else {
      drop_nulls(*it);
      ++it;
    }
  }
}

}  // namespace

nlohmann::json resolve_includes(const nlohmann::json& document, const fs::path& directory, const JsonFileLoader& load) {
  nlohmann::json out = resolve(document, directory, load, "", 0);
  drop_nulls(out);
  return out;
}

}  // namespace dfc::coupler
