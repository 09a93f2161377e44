#pragma once
// Mohr–Coulomb with tension cut-off, elastic–perfectly plastic, as FLAC3D
// implements it (docs/theory/fdm.md §4): non-associated shear flow (dilation angle
// ψ), associated tension flow, the shear/tension choice by distance, the apex
// correction, and the return resolved along the principal directions of the
// elastic trial stress.
#include <array>
#include <memory>

#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/constitutive/mohr_coulomb_return.hpp"

namespace dfc::constitutive {

class MohrCoulombModel final : public ConstitutiveModel {
 public:
  static constexpr std::string_view kKeyword = "mohr_coulomb";
  static constexpr std::string_view kSummary =
      "Mohr-Coulomb shear yield with non-associated flow and a tension cut-off, perfectly plastic (FLAC3D form)";
  /// History per tetrahedron (state_names order).
  enum StateIndex : std::size_t { kPlasticShearStrain = 0, kPlasticTensileStrain = 1, kFailureNow = 2, kStateSize = 3 };

  MohrCoulombModel(ElasticModuli moduli, const MohrCoulombStrength& strength);
  [[nodiscard]] static std::unique_ptr<ConstitutiveModel> from_config(ConfigReader& material);

  [[nodiscard]] std::string_view keyword() const override { return kKeyword; }
  [[nodiscard]] std::size_t state_size() const override { return kStateSize; }
  [[nodiscard]] std::span<const std::string_view> state_names() const override;
  void update(const StrainIncrement& increment, Stress& stress, StateSpan state) const override;
  [[nodiscard]] ElasticModuli stiffest_moduli() const override { return moduli_; }
  [[nodiscard]] bool needs_mean_stress_averaging() const override { return true; }

  [[nodiscard]] const MohrCoulombConstants& constants() const { return constants_; }
  /// F_s of a stress tensor (> 0 outside the shear surface), Pa.
  [[nodiscard]] double shear_function(const Stress& stress) const;

 private:
  ElasticModuli moduli_;
  MohrCoulombStrength strength_;
  MohrCoulombConstants constants_;
};

}  // namespace dfc::constitutive
