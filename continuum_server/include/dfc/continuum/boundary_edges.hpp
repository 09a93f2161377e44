#pragma once
// The boundary of a triangulated body: the edges that belong to one triangle
// only, oriented as in that (counter-clockwise) triangle, so with the body on
// their left (docs/continuum_pile.md §4: the boundary the remeshing keeps).
#include <span>
#include <vector>

#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

[[nodiscard]] std::vector<Edge> boundary_edges(std::span<const Triangle> triangles);

}  // namespace dfc::continuum
