#include "dfc/dem/linear_pbond_law.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace dfc::dem {

std::vector<ParameterSpec> LinearPbondLaw::parameter_specs() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const Bounds positive{0.0, inf, true};
  const Bounds non_negative{0.0, inf, false};
  // Upscaling (docs/theory/upscaling_and_pcrm.md §1–2): moduli, ratios and strengths stay fixed
  // (stiffnesses follow the radii through the deformability method); only the
  // bonding gap, a length, scales with S.
  return {
      {"emod_pa", "Pa", std::nullopt, "effective modulus E* of the linear part, k_n = pi E* R_min^2/(R1+R2)", positive, 0.0},
      {"kratio", "-", 1.0, "normal-to-shear stiffness ratio kappa* of the linear part", positive, 0.0},
      {"friction", "-", 0.5, "Coulomb friction coefficient mu of the linear part", non_negative, 0.0},
      {"damping_ratio_normal", "-", 0.0, "normal viscous damping of the linear part, fraction of critical", Bounds{0.0, 1.0}, 0.0},
      {"pb_emod_pa", "Pa", std::nullopt, "bond effective modulus Ebar*, kbar_n = Ebar*/(R1+R2) [Pa/m]", positive, 0.0},
      {"pb_kratio", "-", 1.0, "bond normal-to-shear stiffness ratio kappabar*", positive, 0.0},
      {"pb_rmul", "-", 1.0, "bond radius multiplier lambdabar: Rbar = lambdabar min(R1, R2)", positive, 0.0},
      {"pb_mcf", "-", 1.0, "moment-contribution factor betabar of the peak stresses", Bounds{0.0, 1.0}, 0.0},
      {"pb_ten_pa", "Pa", std::nullopt, "bond tensile strength sigmabar_c", positive, 0.0},
      {"pb_coh_pa", "Pa", std::nullopt, "bond cohesion cbar", positive, 0.0},
      {"pb_fa_deg", "deg", 0.0, "bond friction angle phibar: tau_c = cbar - sigma tan(phibar)", Bounds{0.0, 90.0, false}, 0.0},
      {"bond_gap_m", "m", 0.0, "pairs whose surface gap is at most this at start are bonded", non_negative, 1.0},
      {"damping_ratio_shear", "-", 0.0, "shear viscous damping of the linear part, fraction of critical, cut while it slides", Bounds{0.0, 1.0},
       0.0},
  };
}

std::vector<HistoryColumn> LinearPbondLaw::history_columns() {
  return {{"bond_state", "-"},  {"bond_normal_force", "N"}, {"bond_shear_force_x", "N"}, {"bond_shear_force_y", "N"},
          {"bond_shear_force_z", "N"}, {"bond_twist_moment", "N m"}, {"bond_bend_moment_x", "N m"}, {"bond_bend_moment_y", "N m"},
          {"bond_bend_moment_z", "N m"}, {"shear_force_x", "N"}, {"shear_force_y", "N"}, {"shear_force_z", "N"}, {"previous_normal_x", "-"}, {"previous_normal_y", "-"}, {"previous_normal_z", "-"}};
}

LinearPbondLaw LinearPbondLaw::from_parameters(std::span<const double> v) {
  return {.emod = v[0], .kratio = v[1], .friction = v[2], .damping_ratio_normal = v[3], .bond_emod = v[4], .bond_kratio = v[5],
          .radius_multiplier = v[6], .moment_factor = v[7], .tensile_strength = v[8], .cohesion = v[9],
          .tan_friction_angle = std::tan(v[10] * std::numbers::pi / 180.0), .bond_gap = v[11], .damping_ratio_shear = v[12]};
}

}  // namespace dfc::dem
