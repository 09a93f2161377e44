#include "dfc/dem/linear_pbond_law.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace dfc::dem {

std::vector<HistoryColumn> LinearPbondLaw::history_columns() {
  return {{"bond_state", "-"},  {"bond_normal_force", "N"}, {"bond_shear_force_x", "N"}, {"bond_shear_force_y", "N"},
          {"bond_shear_force_z", "N"}, {"bond_twist_moment", "N m"}, {"bond_bend_moment_x", "N m"}, {"bond_bend_moment_y", "N m"},
          {"bond_bend_moment_z", "N m"}, {"shear_force_x", "N"}, {"shear_force_y", "N"}, {"shear_force_z", "N"}, {"previous_normal_x", "-"}, {"previous_normal_y", "-"}, {"previous_normal_z", "-"}};
}

LinearPbondLaw LinearPbondLaw::from_parameters(const LawParameters& p) {
  return {.emod = p["emod_pa"], .kratio = p["kratio"], .friction = p["friction"], .damping_ratio_normal = p["damping_ratio_normal"],
          .bond_emod = p["pb_emod_pa"], .bond_kratio = p["pb_kratio"], .radius_multiplier = p["pb_rmul"], .moment_factor = p["pb_mcf"],
          .tensile_strength = p["pb_ten_pa"], .cohesion = p["pb_coh_pa"], .tan_friction_angle = std::tan(p["pb_fa_deg"] * std::numbers::pi / 180.0),
          .bond_gap = p["bond_gap_m"], .damping_ratio_shear = p["damping_ratio_shear"]};
}

}  // namespace dfc::dem
