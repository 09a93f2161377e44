#pragma once
// Geostatic initial stress (docs/theory/fdm.md §2(c)), so that a run under gravity
// can start in equilibrium.
#include "dfc/fdm/types.hpp"

namespace dfc::fdm {

struct GeostaticStress {
  double k0 = 0.5;     ///< σh/σv, -
  double z_top = 0.0;  ///< m, elevation of the free surface (depth 0)
};

/// Tension-positive stress at elevation z under gravity magnitude g (m/s²):
/// σv = ρ g (z_top − z) compressive, σh = K0 σv, no shear:
/// σ_zz = −σv, σ_xx = σ_yy = −K0 σv. Zero above z_top.
[[nodiscard]] Stress geostatic_stress(const GeostaticStress& profile, double density, double gravity_magnitude, double z);

}  // namespace dfc::fdm
