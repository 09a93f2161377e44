#pragma once
// Named materials: calibrated parameter sets from the papers (docs/references.md), selected in a
// scenario with "material": {"preset": "<name>"}. Keys given next to "preset"
// override the preset's values (e.g. a saturated density).
#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace dfc::constitutive {

struct NamedMaterial {
  std::string_view name;
  std::string_view source;    ///< where the values come from
  std::string_view material;  ///< the material object (JSON): "model", "density_kg_m3" and the model's parameters
};

[[nodiscard]] std::span<const NamedMaterial> named_materials();
/// nullptr when unknown.
[[nodiscard]] const NamedMaterial* find_named_material(std::string_view name);
/// The preset's material object with `overrides` (every key but "preset") applied.
[[nodiscard]] nlohmann::json expand_named_material(const NamedMaterial& preset, const nlohmann::json& overrides);
/// For --help: one line per preset.
[[nodiscard]] std::string describe_named_materials();

}  // namespace dfc::constitutive
