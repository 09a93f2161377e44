#pragma once
// Mesh generators for the scenarios (DESIGN §6): boxes, and a thick-walled
// cylinder around a cylindrical cavity (the DEM region) graded towards it.
#include <array>

#include "dfc/fdm/mesh.hpp"

namespace dfc::fdm {

/// Axis-aligned box [origin, origin + size]. Face groups "xmin" … "zmax".
struct BoxSpec {
  Vec3 origin = Vec3::Zero();                 ///< m
  Vec3 size = Vec3::Ones();                   ///< m, each > 0
  std::array<Index, 3> zones = {1, 1, 1};     ///< zone counts along x, y, z, each >= 1
};

/// Annulus Ri <= r <= Ro around the z axis, full 360°, z_bottom <= z <= z_bottom + height.
/// Face groups "inner" (cavity wall, normals towards the axis), "outer", "bottom", "top".
/// Gridpoints lie on the circles (the walls are faceted polygons); the 0/360° seam
/// shares its gridpoints.
struct CylinderCavitySpec {
  double inner_radius = 0.5;    ///< m, > 0
  double outer_radius = 2.0;    ///< m, > inner_radius
  double z_bottom = 0.0;        ///< m
  double height = 1.0;          ///< m, > 0
  Index zones_radial = 4;       ///< >= 1
  Index zones_around = 16;      ///< >= 3 (full circle)
  Index zones_vertical = 2;     ///< >= 1
  /// Geometric grading: Δr_{k+1} = grading_ratio · Δr_k counting outwards, so a
  /// ratio > 1 makes the zones finer towards the inner wall. 1 = uniform.
  double grading_ratio = 1.0;
};

[[nodiscard]] Mesh make_box(const BoxSpec& spec);
[[nodiscard]] Mesh make_cylinder_cavity(const CylinderCavitySpec& spec);

/// Radii of the radial gridpoint rings of `spec` (zones_radial + 1 values, first
/// = inner radius, last = outer radius exactly).
[[nodiscard]] std::vector<double> graded_radii(const CylinderCavitySpec& spec);

}  // namespace dfc::fdm
