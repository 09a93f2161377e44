#pragma once
// A structured annular strip a0 ≤ r ≤ b, 0 ≤ z ≤ h of the r–z half-plane cut
// into triangles: the body of the cylindrical cavity test (docs/continuum_pile.md
// §7). Radial spacing geometric (fine at the cavity), each quadrilateral split
// into two triangles along alternating diagonals so that no direction is favoured.
#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

struct StripMeshSpec {
  double inner_radius = 1.0;  ///< m
  double outer_radius = 100.0;  ///< m
  double height = 0.1;  ///< m
  Index radial_divisions = 40;
  Index vertical_divisions = 1;
  /// Ratio of consecutive radial spacings outwards (> 1: fine at the cavity).
  double radial_ratio = 1.1;
};

/// Node groups "inner", "outer", "bottom", "top"; edge groups "inner" and
/// "outer" (the cylindrical walls, oriented with the body on the left).
[[nodiscard]] AxisymmetricMesh strip_mesh(const StripMeshSpec& spec);

}  // namespace dfc::continuum
