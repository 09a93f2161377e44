#pragma once
// The self-weight stress field a generated model starts from (docs/dem_generation.md):
//   sigma_v(z) = gamma (z_surface - z) + q,   sigma_h(z) = K0 sigma_v(z),
// compression positive, gamma = rho_bulk |N g| the unit weight of the body
// (rho_bulk = rho_s (1 - n)), q a surcharge on the surface. Above the surface
// only the surcharge acts.
#include <algorithm>

namespace dfc::dem {

struct StressProfile {
  double surface_z = 0.0;    ///< m
  double unit_weight = 0.0;  ///< N/m3, rho_bulk |g| (g already N g)
  double k0 = 1.0;           ///< -, sigma_h / sigma_v
  double surcharge = 0.0;    ///< Pa

  [[nodiscard]] double vertical(double z) const noexcept { return unit_weight * std::max(0.0, surface_z - z) + surcharge; }
  [[nodiscard]] double horizontal(double z) const noexcept { return k0 * vertical(z); }
};

}  // namespace dfc::dem
