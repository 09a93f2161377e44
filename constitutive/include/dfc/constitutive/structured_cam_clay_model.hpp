#pragma once
// Structured (bonded) Modified Cam Clay for soft rocks (Ciantia et al. 2024 §2.2, Table 2;
// Monforte et al. 2019; docs/theory/fdm.md §3): an MCC ellipse translated into
// tension by the bonding p_t, sized by p_c = p_s + (1+k) p_t, with a separate
// plastic-potential slope M_g, volumetric/deviatoric hardening of p_s and
// debonding of p_t. The kernels and the choices made where the sources are
// unconfirmed are in cam_clay_return.hpp (and docs/fdm_models.md).
#include <array>
#include <memory>

#include "dfc/constitutive/cam_clay_return.hpp"
#include "dfc/constitutive/elastic_model.hpp"

namespace dfc::constitutive {

class StructuredCamClayModel final : public ConstitutiveModel {
 public:
  static constexpr std::string_view kKeyword = "structured_cam_clay";
  static constexpr std::string_view kSummary =
      "bonded Modified Cam Clay (Ciantia et al. 2024: p_s, p_t, M_f yield, M_g potential, hardening/debonding rho, xi); linear elasticity";
  /// History per tetrahedron (state_names order).
  enum StateIndex : std::size_t { kPs = 0, kPt = 1, kPlasticVolumetricStrain = 2, kPlasticDeviatoricStrain = 3, kStateSize = 4 };

  explicit StructuredCamClayModel(const StructuredCamClayParameters& parameters);
  [[nodiscard]] static std::unique_ptr<ConstitutiveModel> from_config(ConfigReader& material);

  [[nodiscard]] std::string_view keyword() const override { return kKeyword; }
  [[nodiscard]] std::size_t state_size() const override { return kStateSize; }
  [[nodiscard]] std::span<const std::string_view> state_names() const override;
  /// p_s = ps0, p_t = pt0; if the initial stress lies outside that surface,
  /// p_s is raised to put it on the surface (normally consolidated), as a
  /// geostatic stress at N·g may exceed the laboratory p_s0.
  void initialize_state(const Stress& initial_stress, StateSpan state) const override;
  void update(const StrainIncrement& increment, Stress& stress, StateSpan state) const override;
  [[nodiscard]] ElasticModuli stiffest_moduli() const override { return parameters_.moduli; }
  [[nodiscard]] bool needs_mean_stress_averaging() const override { return true; }
  [[nodiscard]] const StructuredCamClayParameters& parameters() const { return parameters_; }

 private:
  /// Returns false when the implicit return fails (the caller sub-steps).
  bool update_once(const SymTensor& strain_increment, Stress& stress, StateSpan state) const;
  void update_substepped(const SymTensor& strain_increment, Stress& stress, StateSpan state, int depth) const;

  StructuredCamClayParameters parameters_;
};

}  // namespace dfc::constitutive
