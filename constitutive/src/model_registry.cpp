#include "dfc/constitutive/model_registry.hpp"

#include <algorithm>
#include <array>

#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/constitutive/mohr_coulomb_model.hpp"
#include "dfc/constitutive/structured_cam_clay_model.hpp"

namespace dfc::constitutive {

namespace {

// The one table of constitutive models (CONTRIBUTING.md §2).
const std::array<ConstitutiveModelEntry, 3> kModels = {{
    {ElasticModel::kKeyword, ElasticModel::kSummary, &ElasticModel::from_config},
    {MohrCoulombModel::kKeyword, MohrCoulombModel::kSummary, &MohrCoulombModel::from_config},
    {StructuredCamClayModel::kKeyword, StructuredCamClayModel::kSummary, &StructuredCamClayModel::from_config},
}};

}  // namespace

std::span<const ConstitutiveModelEntry> constitutive_models() { return kModels; }

const ConstitutiveModelEntry* find_constitutive_model(std::string_view keyword) {
  const auto it = std::find_if(kModels.begin(), kModels.end(), [&](const auto& entry) { return entry.keyword == keyword; });
  return it == kModels.end() ? nullptr : &*it;
}


}  // namespace dfc::constitutive
