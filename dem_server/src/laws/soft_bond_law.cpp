#include "dfc/dem/soft_bond_law.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace dfc::dem {

std::vector<ParameterSpec> SoftBondLaw::parameter_specs() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const Bounds positive{0.0, inf, true};
  const Bounds non_negative{0.0, inf, false};
  // Upscaling (docs/theory/upscaling_and_pcrm.md §1–2): modulus, ratios, strengths and the
  // softening factors stay fixed; the bonding gap scales with S.
  return {
      {"sb_emod_pa", "Pa", std::nullopt, "effective modulus E* of the bond disc, k_n = E*/(R1+R2) [Pa/m] bonded and unbonded", positive, 0.0},
      {"kratio", "-", 1.0, "normal-to-shear stiffness ratio kappa*", positive, 0.0},
      {"friction", "-", 0.5, "Coulomb friction coefficient mu of the unbonded contact", non_negative, 0.0},
      {"damping_ratio_normal", "-", 0.0, "normal viscous damping of the unbonded contact, fraction of critical", Bounds{0.0, 1.0}, 0.0},
      {"sb_rmul", "-", 1.0, "radius multiplier lambda: Rbar = lambda min(R1, R2)", positive, 0.0},
      {"sb_mcf", "-", 1.0, "moment-contribution factor beta of the peak stresses", Bounds{0.0, 1.0}, 0.0},
      {"sb_ten_pa", "Pa", std::nullopt, "tensile strength sigma_t (start of softening)", positive, 0.0},
      {"sb_coh_pa", "Pa", std::nullopt, "cohesion c of the brittle shear strength", positive, 0.0},
      {"sb_fa_deg", "deg", 0.0, "friction angle phi: tau_c = c - sigma tan(phi)", Bounds{0.0, 90.0, false}, 0.0},
      {"sb_soft", "-", 0.0, "softening factor zeta: softening slope -k_n/zeta (0: brittle in tension)", non_negative, 0.0},
      {"sb_cut", "-", 0.0, "softening tensile strength factor gamma: broken when the softened strength is gamma sigma_t",
       Bounds{0.0, 1.0}, 0.0},
      {"bond_gap_m", "m", 0.0, "pairs whose surface gap is at most this at start are bonded", non_negative, 1.0},
      {"damping_ratio_shear", "-", 0.0, "shear viscous damping of the unbonded contact, fraction of critical, cut while it slides",
       Bounds{0.0, 1.0}, 0.0},
  };
}

std::vector<HistoryColumn> SoftBondLaw::history_columns() {
  return {{"bond_state", "-"},       {"bond_normal_force", "N"},  {"bond_shear_force_x", "N"}, {"bond_shear_force_y", "N"},
          {"bond_shear_force_z", "N"}, {"bond_twist_moment", "N m"}, {"bond_bend_moment_x", "N m"}, {"bond_bend_moment_y", "N m"},
          {"bond_bend_moment_z", "N m"}, {"peripheral_elongation", "m"}, {"max_peripheral_elongation", "m"},
          {"shear_force_x", "N"},      {"shear_force_y", "N"},     {"shear_force_z", "N"}};
}

SoftBondLaw SoftBondLaw::from_parameters(std::span<const double> v) {
  return {.emod = v[0], .kratio = v[1], .friction = v[2], .damping_ratio_normal = v[3], .radius_multiplier = v[4], .moment_factor = v[5],
          .tensile_strength = v[6], .cohesion = v[7], .tan_friction_angle = std::tan(v[8] * std::numbers::pi / 180.0),
          .softening_factor = v[9], .cut_factor = v[10], .bond_gap = v[11], .damping_ratio_shear = v[12]};
}

}  // namespace dfc::dem
