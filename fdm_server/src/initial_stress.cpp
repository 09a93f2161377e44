#include "dfc/fdm/initial_stress.hpp"

#include <algorithm>

namespace dfc::fdm {

Stress geostatic_stress(const GeostaticStress& profile, double density, double gravity_magnitude, double z) {
  const double depth = std::max(0.0, profile.z_top - z);
  const double vertical = density * gravity_magnitude * depth;  // σv, compression positive (§2(c))
  return Stress{-profile.k0 * vertical, -profile.k0 * vertical, -vertical, 0.0, 0.0, 0.0};
}

}  // namespace dfc::fdm
