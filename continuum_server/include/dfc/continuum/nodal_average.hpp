#pragma once
// The average nodal volumetric strain of Bonet & Burton (1998) in increments
// (docs/continuum_pile.md §3): each node takes the volume-weighted mean of its
// triangles' values, each triangle the mean of its three nodes'. Applied to the
// volumetric strain increment it removes the volumetric locking of constant-
// strain triangles (one constraint per node instead of one per triangle).
#include <span>
#include <vector>

#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

/// Per triangle, the mean over its nodes of the `weights`-weighted nodal means
/// of `values`. A uniform field is returned unchanged.
[[nodiscard]] std::vector<double> nodal_average(std::span<const Triangle> triangles, Index node_count,
                                                std::span<const double> weights, std::span<const double> values);

}  // namespace dfc::continuum
