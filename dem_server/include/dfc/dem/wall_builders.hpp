#pragma once
// Meshes of the standard rigid walls: a square patch of a plane (floor,
// platen), the closed polygonal cylinder of a pile with a flat tip and the
// open-ended tube of a tubular pile (Ciantia et al. 2024, §3).
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
  /// m, > 0: an open-ended tube whose bore has this radius (wall thickness
  /// radius - inner_radius); 0: a closed cylinder
  double inner_radius = 0.0;
};

/// Closed cylinder: `sides` rectangular side panels (2 triangles each) and a
/// flat fan of triangles at each end; outward normals.
[[nodiscard]] WallMesh make_closed_cylinder_mesh(const CylinderGeometry& g);

/// Open-ended tube (g.inner_radius in (0, g.radius)): a flat annulus at the
/// tip (2 triangles per side, normal -z), then the inner shaft (normals
/// towards the axis), then the outer shaft (normals outward); open at the top.
/// The annulus comes first so that it owns both rims (ties go to the lower
/// facet index, wall_contacts.hpp), as the flat tip of the closed cylinder does.
[[nodiscard]] WallMesh make_open_tube_mesh(const CylinderGeometry& g);

/// The pile's mesh: the open tube when g.inner_radius > 0, else the closed cylinder.
[[nodiscard]] WallMesh make_pile_mesh(const CylinderGeometry& g);

}  // namespace dfc::dem
