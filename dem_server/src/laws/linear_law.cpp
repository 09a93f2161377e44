#include "dfc/dem/linear_law.hpp"

#include <limits>

namespace dfc::dem {

std::vector<HistoryColumn> LinearLaw::history_columns() {
  return {{"shear_force_x", "N"}, {"shear_force_y", "N"}, {"shear_force_z", "N"}};
}

LinearLaw LinearLaw::from_parameters(const LawParameters& p) {
  return {.kn = p["kn_n_m"], .ks = p["ks_n_m"], .friction = p["friction"], .damping_ratio_normal = p["damping_ratio_normal"],
          .damping_ratio_shear = p["damping_ratio_shear"]};
}

}  // namespace dfc::dem
