#pragma once
// Internal helper of the cylinder_cavity mesh: the structured hexahedral mesh
// of a solid disc r <= R (extruded over layers of gridpoints), an "O-grid"
// (docs/fdm_models.md, "The base under the cavity"). A solid disc has no
// single (r, θ) lattice (the axis would be a degenerate edge with zero-volume
// zones), so it is split into two lattices:
//  - the core, a square rotated by 45° (a "diamond") with corners on the x
//    and y axes at distance a = kCoreHalfDiagonal · R, one lattice of
//    m × m zones (m = zones_around / 4), affine in the diamond;
//  - the ring between the diamond's perimeter (4 m gridpoints) and the
//    circle's zones_around gridpoints, joined by straight spokes and split
//    into ring_zones layers along them.
// The circle's gridpoints are the annulus's (given, shared), so the disc and
// the annulus around it form one conforming mesh.
#include <functional>
#include <string>
#include <vector>

#include "dfc/fdm/mesh.hpp"

namespace dfc::fdm::detail {

/// Distance from the axis to the diamond's corners over the disc's radius:
/// the diamond's sides then lie at 0.5 R, so the ring is 0.29 R to 0.5 R
/// thick and the core's zones (edge R / m) are 64 % of the circle's arcs
/// (2π R / zones_around): near-square zones on both sides of the spokes.
inline constexpr double kCoreHalfDiagonal = 0.7071067811865476;  // 1/√2

/// Layers of ring zones along the spokes: the ring's mean width (0.4 R, the
/// mean of 0.29 R and 0.5 R) over the mean zone edge around it (the mean of
/// the core's R / m and the circle's 2π R / zones_around), at least 1.
[[nodiscard]] Index disc_ring_zones(Index zones_around);

/// Gridpoint of the disc's boundary circle at angle index j (0 .. zones_around - 1,
/// counter-clockwise from +x) on gridpoint level k.
using CircleNode = std::function<Index(Index j, Index k)>;

/// Appends the disc's gridpoints (on the levels and at the heights of the
/// circle's gridpoints, levels 0 .. layers) and its zones to `mesh`, and its
/// faces on level 0 to `bottom_group` and on level `layers` to each of `top_groups`.
/// zones_around must be a multiple of 4 (the diamond's sides take a quarter each).
void add_disc_ogrid(Mesh& mesh, Index zones_around, Index layers, const CircleNode& circle_node, const std::string& bottom_group,
                    const std::vector<std::string>& top_groups);

}  // namespace dfc::fdm::detail
