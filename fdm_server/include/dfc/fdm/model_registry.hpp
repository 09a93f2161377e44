#pragma once
// The constitutive-model registry: one table, keyword → factory, each entry
// declaring its parameters (CONTRIBUTING.md §2: one registry table per plug-in family).
// Adding a model = one row in model_registry.cpp.
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "dfc/fdm/constitutive_model.hpp"
#include "dfc/fdm/model_parameter.hpp"

namespace dfc {
class ConfigReader;
}

namespace dfc::fdm {

struct ConstitutiveModelEntry {
  std::string_view keyword;
  std::string_view summary;
  std::span<const ModelParameter> parameters;
  /// Reads the model's parameters from the material object (not "model" or "density_kg_m3").
  std::unique_ptr<ConstitutiveModel> (*create)(ConfigReader& material);
};

[[nodiscard]] std::span<const ConstitutiveModelEntry> constitutive_models();
/// nullptr when unknown.
[[nodiscard]] const ConstitutiveModelEntry* find_constitutive_model(std::string_view keyword);
/// Human-readable list of models and their parameters with units (for --help).
[[nodiscard]] std::string describe_constitutive_models();

}  // namespace dfc::fdm
