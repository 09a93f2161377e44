#pragma once
// The state transfer's search (docs/continuum_pile.md §5): for each point, the
// triangle of a mesh that contains it, or, for a point outside every triangle,
// the triangle with the nearest centroid.
#include <array>
#include <span>
#include <vector>

#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

/// Barycentric coordinates of p in the triangle abc (all ≥ 0 inside, sum 1).
[[nodiscard]] std::array<double, 3> barycentric_coordinates(const Point& p, const Point& a, const Point& b, const Point& c);

/// Brute force, O(points × triangles): meant for the meshes of the tests; a
/// bucket grid replaces it when meshes grow.
[[nodiscard]] std::vector<Index> containing_triangles(std::span<const Point> nodes, std::span<const Triangle> triangles,
                                                      std::span<const Point> points);

}  // namespace dfc::continuum
