#pragma once
// A structured triangle mesh: the grid radii[i] × levels[j] mapped into the
// r–z half-plane, each quadrilateral split into two triangles along
// alternating diagonals so that no direction is favoured (the cavity meshes,
// cavity_meshes.hpp, and the soil of the pile, pile_mesh.hpp).
#include <functional>
#include <string>
#include <vector>

#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

/// i runs outwards, j along the walls, and `place` keeps the orientation
/// (i, j) → (r, z), so the triangles come out counter-clockwise. Node and edge
/// groups "inner" (i = 0), "outer" (last i), `first_side` (j = 0) and
/// `last_side` (last j), edges oriented with the body on the left.
[[nodiscard]] AxisymmetricMesh mapped_grid(const std::vector<double>& radii, const std::vector<double>& levels,
                                           const std::function<Point(double, double)>& place,
                                           const std::string& first_side, const std::string& last_side);

}  // namespace dfc::continuum
