#pragma once
// Re-triangulation of a deformed body (docs/continuum_pile.md §4): the
// constrained Delaunay triangulation (CGAL Constrained_Delaunay_triangulation_2)
// of its nodes with its boundary edges as constraints, restricted to the
// body, optionally refined by CGAL's Delaunay refinement (Delaunay_mesher_2)
// until no triangle has an angle below a bound. The existing nodes are kept
// (PFEM: the particles carry the nodal fields); refinement adds nodes inside
// and on the boundary edges, never moving the boundary, so the volume is the same.
#include <limits>
#include <span>
#include <vector>

#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

struct Retriangulation {
  /// Nodes added by the refinement; their indices follow the existing nodes'.
  std::vector<Point> added_nodes;
  /// For each added node, the index in `boundary` of the edge it lies on, or kInterior.
  std::vector<Index> boundary_edge_of_added;
  /// Counter-clockwise triangles over the existing and the added nodes.
  std::vector<Triangle> triangles;
  static constexpr Index kInterior = std::numeric_limits<Index>::max();
};

/// The constrained Delaunay triangulation of `nodes` with `boundary` (closed,
/// body on the left of each edge) as constraints, keeping the faces inside the
/// body; with `minimum_angle_deg` > 0 (at most about 30°, CGAL's bound for
/// termination) refined until every triangle's smallest angle reaches it.
[[nodiscard]] Retriangulation delaunay_retriangulation(std::span<const Point> nodes, std::span<const Edge> boundary,
                                                       double minimum_angle_deg = 0.0);

}  // namespace dfc::continuum
