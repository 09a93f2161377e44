#include "dfc/coupler/scenario_variants.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "dfc/common/echo.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/coupler/scenario.hpp"

namespace dfc::coupler {

namespace {

bool valid_label(const std::string& label) {
  return is_single_folder_name(label) && std::all_of(label.begin(), label.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
}

}  // namespace

std::vector<ScenarioVariant> expand_variants(const nlohmann::json& document) {
  if (!document.is_object() || !document.contains("variants")) return {{"", document}};
  const nlohmann::json& list = document.at("variants");
  if (!list.is_array() || list.empty())
    throw ConfigError("variants", "expected a non-empty array of {\"label\": ..., \"patch\": {...}}; remove the key for a single run");
  nlohmann::json base = document;
  base.erase("variants");
  std::vector<ScenarioVariant> out;
  std::set<std::string> labels;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string path = "variants[" + std::to_string(k) + "]";
    const nlohmann::json& entry = list[k];
    if (!entry.is_object()) throw ConfigError(path, "expected an object {\"label\": ..., \"patch\": {...}}");
    for (const auto& item : entry.items())
      if (item.key() != "label" && item.key() != "patch" && item.key() != "comment")
        throw ConfigError(path + "." + echoed(item.key()), "unknown key; a variant has \"label\" and \"patch\"");
    if (!entry.contains("label") || !entry.at("label").is_string() || !valid_label(entry.at("label").get<std::string>()))
      throw ConfigError(path + ".label", "expected a name of letters, digits, '_', '-' or '.', not '.' or '..' (it names the results folder)");
    const std::string label = entry.at("label").get<std::string>();
    if (!labels.insert(label).second) throw ConfigError(path + ".label", "another variant is already labelled \"" + echoed(label) + "\"");
    const nlohmann::json patch = entry.value("patch", nlohmann::json::object());
    if (!patch.is_object()) throw ConfigError(path + ".patch", "expected an object (a JSON Merge Patch of the scenario)");
    if (patch.contains("variants")) throw ConfigError(path + ".patch.variants", "a variant cannot have variants of its own");
    nlohmann::json variant = base;
    variant.merge_patch(patch);
    // Malformed name or output are left for parse_scenario to name.
    const bool named = variant.contains("name") && variant.at("name").is_string();
    if (named) variant["name"] = variant.at("name").get<std::string>() + "_" + label;
    if (!variant.contains("output") || variant.at("output").is_object()) {
      nlohmann::json& output = variant["output"];
      const bool given = output.contains("directory") && output.at("directory").is_string();
      const std::string base_name = base.contains("name") && base.at("name").is_string() ? base.at("name").get<std::string>() : "scenario";
      output["directory"] = (given ? output.at("directory").get<std::string>() : "results/" + base_name) + "/" + label;
    }
    out.push_back({label, std::move(variant)});
  }
  return out;
}

}  // namespace dfc::coupler
