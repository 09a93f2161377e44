#pragma once
// The soil of the continuum pile (docs/continuum_pile.md §6): the cylinder
// 0 ≤ r ≤ R, 0 ≤ z ≤ H in the r–z half-plane, a structured triangle mesh
// (mapped_grid.hpp) with node columns at the pile's inner and outer radii,
// fine at the pile's wall and at the surface z = H, where the pile's tip
// starts.
#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

struct PileMeshSpec {
  double radius = 0.05;              ///< R, m (the container)
  double height = 0.12;              ///< H, m (the surface)
  double pile_inner_radius = 0.003;  ///< r_i, m; 0: a solid punch (no bore)
  double pile_outer_radius = 0.004;  ///< r_o, m
  Index bore_divisions = 6;          ///< 0 ≤ r ≤ r_i, graded fine at r_i
  Index wall_divisions = 4;          ///< r_i ≤ r ≤ r_o, uniform
  Index outside_divisions = 20;      ///< r_o ≤ r ≤ R, graded fine at r_o
  /// Ratio of consecutive radial spacings away from the pile's wall.
  double radial_ratio = 1.15;
  Index vertical_divisions = 30;
  /// Ratio of consecutive vertical spacings downwards from the surface.
  double vertical_ratio = 1.1;
};

/// Node and edge groups "axis" (r = 0), "outer" (r = R), "bottom" (z = 0)
/// and "top" (z = H); edges oriented with the body on the left.
[[nodiscard]] AxisymmetricMesh pile_mesh(const PileMeshSpec& spec);

}  // namespace dfc::continuum
