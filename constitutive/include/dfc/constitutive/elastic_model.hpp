#pragma once
// Isotropic linear elasticity in rate form: Δσ = 2G Δe + K Δε_v I.
#include <array>
#include <memory>

#include "dfc/constitutive/constitutive_model.hpp"

namespace dfc {
class ConfigReader;
}

namespace dfc::constitutive {

/// K = E/(3(1−2ν)), G = E/(2(1+ν)).
[[nodiscard]] ElasticModuli moduli_from_young_poisson(double young_modulus, double poisson_ratio);
/// Reads E and nu, or K and G, from a material object (either pair, not both; declared in dfc/common/sections/fdm_sections.hpp).
[[nodiscard]] ElasticModuli read_elastic_moduli(ConfigReader& material);
/// Hooke's law in increments: Δσ = 2G dev(Δε) + K tr(Δε) I (tension positive).
[[nodiscard]] Stress elastic_stress_increment(const ElasticModuli& moduli, const SymTensor& strain_increment);

class ElasticModel final : public ConstitutiveModel {
 public:
  static constexpr std::string_view kKeyword = "elastic";
  static constexpr std::string_view kSummary = "isotropic linear elasticity (give E and nu, or K and G)";

  explicit ElasticModel(ElasticModuli moduli);
  [[nodiscard]] static ElasticModel from_young_poisson(double young_modulus, double poisson_ratio);
  /// Reads the parameters above from the material object (the registry factory).
  [[nodiscard]] static std::unique_ptr<ConstitutiveModel> from_config(ConfigReader& material);

  [[nodiscard]] std::string_view keyword() const override { return kKeyword; }
  void update(const StrainIncrement& increment, Stress& stress, StateSpan state) const override;
  [[nodiscard]] ElasticModuli stiffest_moduli() const override { return moduli_; }
  [[nodiscard]] const ElasticModuli& moduli() const { return moduli_; }

 private:
  ElasticModuli moduli_;
};

}  // namespace dfc::constitutive
