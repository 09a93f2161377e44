#pragma once
// Re-triangulation of a deformed body (docs/continuum_pile.md §4): the
// constrained Delaunay triangulation (CGAL Constrained_Delaunay_triangulation_2)
// of its nodes with its boundary edges as constraints, restricted to the
// body. The nodes are kept (PFEM: the particles carry the nodal fields), so
// only the connectivity changes; the boundary, hence the volume, is the same.
#include <span>
#include <vector>

#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

/// Counter-clockwise triangles of the constrained Delaunay triangulation of
/// `nodes` with `boundary` (closed, body on the left of each edge) as
/// constraints, keeping the faces inside the body.
[[nodiscard]] std::vector<Triangle> delaunay_retriangulation(std::span<const Point> nodes, std::span<const Edge> boundary);

}  // namespace dfc::continuum
