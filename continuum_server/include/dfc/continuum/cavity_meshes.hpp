#pragma once
// The structured triangle meshes of the cavity tests (docs/continuum_pile.md
// §7): a graded grid of quadrilaterals, each split into two triangles along
// alternating diagonals so that no direction is favoured, mapped onto
// - an annular strip a₀ ≤ r ≤ b, 0 ≤ z ≤ h (the cylindrical cavity, plane
//   strain along the axis), or
// - a quarter annulus a₀ ≤ ρ ≤ b, 0 ≤ θ ≤ 90° of the meridian plane
//   (r = ρ cos θ, z = ρ sin θ: the spherical cavity, its equator z = 0 a
//   symmetry plane).
#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

struct CavityMeshSpec {
  double inner_radius = 1.0;    ///< a₀, m
  double outer_radius = 100.0;  ///< b, m
  Index radial_divisions = 40;
  /// Ratio of consecutive radial spacings outwards (> 1: fine at the cavity).
  double radial_ratio = 1.1;
  /// Divisions along z (strip) or along the quarter circle (quarter annulus).
  Index tangential_divisions = 1;
  double strip_height = 0.1;  ///< h, m (strip only)
};

/// Node and edge groups "inner", "outer", "bottom" (z = 0), "top" (z = h);
/// edges oriented with the body on the left. With a few radial divisions and
/// many along z it is also a column (the consolidation test).
[[nodiscard]] AxisymmetricMesh strip_mesh(const CavityMeshSpec& spec);
/// Node and edge groups "inner", "outer", "equator" (z = 0), "axis" (r = 0).
[[nodiscard]] AxisymmetricMesh quarter_annulus_mesh(const CavityMeshSpec& spec);

}  // namespace dfc::continuum
