#pragma once
// The "grid" snapshot arrays of SPEC.md §6.4 for a state on an fdm::Mesh,
// shared by fdm_server and the reference continua built on the same mesh.
#include <span>
#include <vector>

#include "dfc/fdm/types.hpp"
#include "dfc/fdm/mesh.hpp"
#include "dfc/protocol/array.hpp"

namespace dfc::fdm {

/// node_position, node_displacement, node_velocity (f64 [N,3]), zone_nodes
/// (i64 [M,8], VTK hexahedron order) and zone_stress (f64 [M,6], XDMF Tensor6
/// order xx, xy, xz, yy, yz, zz); with `external_force` (one per node) also
/// node_external_force (f64 [N,3]): the coupling's force on each node, from
/// which the traction on the coupling wall can be read (tools/open_pile.py).
[[nodiscard]] std::vector<protocol::Array> grid_snapshot(const Mesh& mesh, std::span<const Vec3> displacement,
                                                         std::span<const Vec3> velocity, std::span<const Stress> zone_stress,
                                                         std::span<const Vec3> external_force = {});

}  // namespace dfc::fdm
