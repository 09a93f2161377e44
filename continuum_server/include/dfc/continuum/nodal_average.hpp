#pragma once
// Averages between triangles and nodes (docs/continuum_pile.md §3, §5).
// - The average nodal volumetric strain of Bonet & Burton (1998) in
//   increments: each node takes the volume-weighted mean of its triangles'
//   values, each triangle the mean of its three nodes'. Applied to the
//   volumetric strain increment it reduces the volumetric locking of
//   constant-strain triangles (one constraint per node instead of one per
//   triangle).
// - The same two halves transfer a triangle field to the triangles of a new
//   connectivity on the same nodes (the remesh): recovered at the nodes from
//   the old triangles, interpolated at the new triangles' centroids.
#include <span>
#include <vector>

#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

/// Per node, the `weights`-weighted mean of `values` over the triangles that
/// contain it (0 at a node of no triangle).
[[nodiscard]] std::vector<double> nodal_means(std::span<const Triangle> triangles, Index node_count,
                                              std::span<const double> weights, std::span<const double> values);
/// Per triangle, the mean of its three nodes' values (the linear
/// interpolation of the nodal field at its centroid).
[[nodiscard]] std::vector<double> triangle_means(std::span<const Triangle> triangles, std::span<const double> nodal_values);
/// triangle_means(triangles, nodal_means(triangles, …)). A uniform field is returned unchanged.
[[nodiscard]] std::vector<double> nodal_average(std::span<const Triangle> triangles, Index node_count,
                                                std::span<const double> weights, std::span<const double> values);

}  // namespace dfc::continuum
