#pragma once
// Isotropic linear elasticity in rate form: Δσ = 2G Δe + K Δε_v I.
#include <array>
#include <memory>

#include "dfc/fdm/constitutive_model.hpp"
#include "dfc/fdm/model_parameter.hpp"

namespace dfc {
class ConfigReader;
}

namespace dfc::fdm {

/// The elastic parameters every model of the registry reads (E and ν, or K and G).
inline constexpr std::array<ModelParameter, 4> kElasticParameters = {{
    {"young_modulus_pa", "Pa", "Young's modulus E > 0; give it with poisson_ratio"},
    {"poisson_ratio", "-", "Poisson's ratio nu in (-1, 0.5); give it with young_modulus_pa"},
    {"bulk_modulus_pa", "Pa", "bulk modulus K > 0; alternative to E/nu, give it with shear_modulus_pa"},
    {"shear_modulus_pa", "Pa", "shear modulus G > 0; give it with bulk_modulus_pa"},
}};

/// K = E/(3(1−2ν)), G = E/(2(1+ν)).
[[nodiscard]] ElasticModuli moduli_from_young_poisson(double young_modulus, double poisson_ratio);
/// Reads kElasticParameters from a material object (either pair, not both).
[[nodiscard]] ElasticModuli read_elastic_moduli(ConfigReader& material);
/// Hooke's law in increments: Δσ = 2G dev(Δε) + K tr(Δε) I (tension positive).
[[nodiscard]] Stress elastic_stress_increment(const ElasticModuli& moduli, const SymTensor& strain_increment);

class ElasticModel final : public ConstitutiveModel {
 public:
  static constexpr std::string_view kKeyword = "elastic";
  static constexpr std::string_view kSummary = "isotropic linear elasticity (give E and nu, or K and G)";
  static constexpr const std::array<ModelParameter, 4>& kParameters = kElasticParameters;

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

}  // namespace dfc::fdm
