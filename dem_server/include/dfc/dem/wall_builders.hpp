#pragma once
// Meshes of the standard rigid walls: a square patch of a plane (floor,
// platen) and the closed polygonal cylinder of a pile with a flat tip.
#include "dfc/dem/wall.hpp"

namespace dfc::dem {

/// Square of half-width `half_size` centred on `point`, in the plane with unit
/// normal `normal` (two triangles, right-hand normal = `normal`).
[[nodiscard]] WallMesh make_plane_mesh(const Vec3& point, const Vec3& normal, double half_size);

struct CylinderGeometry {
  double axis_x = 0.0;  ///< m, the axis is vertical through (axis_x, axis_y)
  double axis_y = 0.0;
  double tip_z = 0.0;   ///< m, the flat bottom end
  double radius = 0.0;  ///< m, vertices lie on this circle (inscribed polygon)
  double length = 0.0;  ///< m, the top end is at tip_z + length
  int sides = 24;
};

/// Closed cylinder: `sides` rectangular side panels (2 triangles each) and a
/// flat fan of triangles at each end; outward normals.
[[nodiscard]] WallMesh make_closed_cylinder_mesh(const CylinderGeometry& g);

}  // namespace dfc::dem
