#include "dfc/dem/soft_bond_law.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace dfc::dem {

std::vector<HistoryColumn> SoftBondLaw::history_columns() {
  return {{"bond_state", "-"},       {"bond_normal_force", "N"},  {"bond_shear_force_x", "N"}, {"bond_shear_force_y", "N"},
          {"bond_shear_force_z", "N"}, {"bond_twist_moment", "N m"}, {"bond_bend_moment_x", "N m"}, {"bond_bend_moment_y", "N m"},
          {"bond_bend_moment_z", "N m"}, {"peripheral_elongation", "m"}, {"max_peripheral_elongation", "m"},
          {"shear_force_x", "N"},      {"shear_force_y", "N"},     {"shear_force_z", "N"}};
}

SoftBondLaw SoftBondLaw::from_parameters(const LawParameters& p) {
  return {.emod = p["sb_emod_pa"], .kratio = p["kratio"], .friction = p["friction"], .damping_ratio_normal = p["damping_ratio_normal"],
          .radius_multiplier = p["sb_rmul"], .moment_factor = p["sb_mcf"], .tensile_strength = p["sb_ten_pa"], .cohesion = p["sb_coh_pa"],
          .tan_friction_angle = std::tan(p["sb_fa_deg"] * std::numbers::pi / 180.0), .softening_factor = p["sb_soft"],
          .cut_factor = p["sb_cut"], .bond_gap = p["bond_gap_m"], .damping_ratio_shear = p["damping_ratio_shear"]};
}

}  // namespace dfc::dem
