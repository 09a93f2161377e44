#pragma once
// Internal helper of the mesh generators: hexahedral zones and boundary face
// groups over a logically structured (i,j,k) lattice of gridpoints.
#include <array>
#include <functional>
#include <string>

#include "dfc/fdm/mesh.hpp"

namespace dfc::fdm::detail {

/// Gridpoint index of lattice node (i, j, k); may wrap (periodic direction).
using LatticeNodeIndex = std::function<Index(Index i, Index j, Index k)>;

/// Appends zones (i,j,k), i < counts[0], … in FLAC3D corner order, i fastest.
void add_lattice_zones(Mesh& mesh, const std::array<Index, 3>& counts, const LatticeNodeIndex& node);

/// Adds face group `name`: the faces on lattice side `side` (0: low, 1: high)
/// of direction `axis`, each ordered so that its right-hand normal points out
/// of its zone (checked against the zone centroid).
void add_lattice_face_group(Mesh& mesh, const std::string& name, const std::array<Index, 3>& counts,
                            const LatticeNodeIndex& node, int axis, int side);

}  // namespace dfc::fdm::detail
