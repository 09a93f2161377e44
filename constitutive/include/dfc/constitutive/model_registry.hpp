#pragma once
// The constitutive-model registry: one table, keyword → factory, each entry
// (CONTRIBUTING.md §2: one registry table per plug-in family); each model's
// parameters are declared in dfc/common/sections/fdm_sections.hpp.
// Adding a model = one row in model_registry.cpp.
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "dfc/constitutive/constitutive_model.hpp"

namespace dfc {
class ConfigReader;
}

namespace dfc::constitutive {

struct ConstitutiveModelEntry {
  std::string_view keyword;
  std::string_view summary;
  /// Reads the model's parameters from the material object (not "model" or "density_kg_m3").
  std::unique_ptr<ConstitutiveModel> (*create)(ConfigReader& material);
};

[[nodiscard]] std::span<const ConstitutiveModelEntry> constitutive_models();
/// nullptr when unknown.
[[nodiscard]] const ConstitutiveModelEntry* find_constitutive_model(std::string_view keyword);

}  // namespace dfc::constitutive
