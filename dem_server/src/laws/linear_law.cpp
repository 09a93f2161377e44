#include "dfc/dem/linear_law.hpp"

#include <limits>

namespace dfc::dem {

std::vector<ParameterSpec> LinearLaw::parameter_specs() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  // Upscaling by S (docs/theory/upscaling_and_pcrm.md §1): k = E* pi R^2 / (2R) grows
  // with R, so both stiffnesses scale with S (Thakur et al. 2015); friction and
  // the damping ratio are dimensionless and stay fixed.
  return {
      {"kn_n_m", "N/m", std::nullopt, "normal contact stiffness k_n", Bounds{0.0, inf, true}, 1.0},
      {"ks_n_m", "N/m", std::nullopt, "shear contact stiffness k_s", Bounds{0.0, inf, false}, 1.0},
      {"friction", "-", 0.5, "Coulomb friction coefficient mu: |F_s| <= mu F_n", Bounds{0.0, inf, false}, 0.0},
      {"damping_ratio_normal", "-", 0.0, "normal viscous damping as a fraction beta_n of critical, c_n = 2 beta_n sqrt(m_eff k_n)",
       Bounds{0.0, 1.0, false}, 0.0},
      {"damping_ratio_shear", "-", 0.0,
       "shear viscous damping as a fraction beta_s of critical, c_s = 2 beta_s sqrt(m_eff k_s), cut while the contact slides",
       Bounds{0.0, 1.0, false}, 0.0},
  };
}

std::vector<HistoryColumn> LinearLaw::history_columns() {
  return {{"shear_force_x", "N"}, {"shear_force_y", "N"}, {"shear_force_z", "N"}};
}

LinearLaw LinearLaw::from_parameters(std::span<const double> values) {
  return {.kn = values[0], .ks = values[1], .friction = values[2], .damping_ratio_normal = values[3], .damping_ratio_shear = values[4]};
}

}  // namespace dfc::dem
