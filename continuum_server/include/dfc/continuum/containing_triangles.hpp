#pragma once
// The state transfer's search (docs/continuum_pile.md §5): for each point, the
// triangle of a mesh that contains it, or, for a point outside every triangle,
// the triangle with the nearest centroid.
#include <span>
#include <vector>

#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

/// Brute force, O(points × triangles): meant for the meshes of the tests; a
/// bucket grid replaces it when meshes grow.
[[nodiscard]] std::vector<Index> containing_triangles(std::span<const Point> nodes, std::span<const Triangle> triangles,
                                                      std::span<const Point> points);

}  // namespace dfc::continuum
