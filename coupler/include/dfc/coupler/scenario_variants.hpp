#pragma once
// Scenario variants: one file that describes a family of runs, e.g. the same
// rock at several particle-upscaling factors (issue 3, `ucs_upscaling`).
//
//   "variants": [ {"label": "S1", "patch": {...}}, {"label": "S2", "patch": {...}} ]
//
// Each variant is the scenario without "variants", with its patch applied as a
// JSON Merge Patch (RFC 7386: objects merge key by key, anything else
// replaces, null deletes). Its name becomes "<name>_<label>" and its results go
// to "<output directory>/<label>", so one plot can overlay them all. A
// scenario without "variants" is one run, unchanged.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dfc::coupler {

struct ScenarioVariant {
  std::string label;        ///< empty for a scenario without variants
  nlohmann::json document;  ///< the complete scenario of this run
};

/// The runs `document` describes. Throws dfc::ConfigError naming
/// "variants[k]..." for a malformed list (labels: letters, digits, '_', '-',
/// '.', unique).
[[nodiscard]] std::vector<ScenarioVariant> expand_variants(const nlohmann::json& document);

}  // namespace dfc::coupler
