#pragma once
// Mesh generators for the scenarios and the verification problems (docs/fdm_models.md):
// boxes (optionally graded), a thick-walled cylinder (or a sector of it) around
// a cylindrical cavity graded towards it, and an octant of a spherical shell
// around a spherical cavity.
#include <array>
#include <limits>
#include <optional>
#include <string>

#include "dfc/common/sections/fdm_sections.hpp"
#include "dfc/fdm/mesh.hpp"

namespace dfc::fdm {

/// Default limit of the zone aspect ratio (longest/shortest edge) for the
/// cavity meshes, declared with the key max_aspect_ratio.
inline constexpr double kDefaultMaxAspectRatio = sections::kDefaultMaxAspectRatio;

/// Axis-aligned box [origin, origin + size]. Face groups "xmin" … "zmax".
struct BoxSpec {
  Vec3 origin = Vec3::Zero();                 ///< m
  Vec3 size = Vec3::Ones();                   ///< m, each > 0
  std::array<Index, 3> zones = {1, 1, 1};     ///< zone counts along x, y, z, each >= 1
  /// Per axis, Δ_{k+1}/Δ_k counted in the + direction (> 1: finer at the min
  /// side, < 1: finer at the max side); 1 = uniform.
  std::array<double, 3> grading = {1.0, 1.0, 1.0};
};

/// Annulus Ri <= r <= Ro around the z axis, z_bottom <= z <= z_bottom + height,
/// over 0 <= θ <= angle_deg (360: full circle). Face groups "inner" (cavity
/// wall, normals towards the axis), "outer", "bottom", "top", and for a sector
/// "theta_min" (θ = 0, the plane y = 0) and "theta_max" (θ = angle_deg).
/// Gridpoints lie on the circles (the walls are faceted polygons); a full
/// circle shares its 0/360° seam gridpoints.
///
/// With cavity_floor_z the cavity ends there: below it the body is a solid
/// cylinder, the disc r <= Ri meshed as an O-grid (disc_ogrid.hpp) conforming
/// to the annulus. "inner" is then the cavity's whole wall, side and floor
/// (floor normals up, into the cavity); "cavity_side" and "cavity_floor" are
/// its two parts; "bottom" spans the whole disc r <= Ro. Needs the full
/// circle, zones_around a multiple of 4, and the floor on a zone level
/// (cavity_floor_level).
struct CylinderCavitySpec {
  double inner_radius = 0.5;    ///< m, > 0
  double outer_radius = 2.0;    ///< m, > inner_radius
  double z_bottom = 0.0;        ///< m
  double height = 1.0;          ///< m, > 0
  Index zones_radial = 4;       ///< >= 1
  Index zones_around = 16;      ///< >= 3 for the full circle, >= 1 for a sector
  Index zones_vertical = 2;     ///< >= 1
  /// Geometric grading: Δr_{k+1} = grading_ratio · Δr_k counting outwards, so a
  /// ratio > 1 makes the zones finer towards the inner wall. 1 = uniform.
  double grading_ratio = 1.0;
  double angle_deg = 360.0;     ///< in (0, 360]
  /// Zones with a larger aspect ratio are an error naming them (mesh_quality.hpp);
  /// +∞ disables the check (plane-strain slices one zone thick).
  double max_aspect_ratio = kDefaultMaxAspectRatio;
  /// m, in (z_bottom, z_bottom + height); absent: the cavity spans the whole height.
  std::optional<double> cavity_floor_z;
};

/// One octant (x, y, z >= 0) of the spherical shell Ri <= r <= Ro around a
/// spherical cavity, for spherically symmetric problems with symmetry planes.
/// The octant's spherical triangle is split into three quadrilateral patches
/// meeting at (1,1,1)/√3 (a cubed-sphere-like split without a pole), each a
/// lattice of zones_around × zones_around zones per radial layer.
/// Face groups "inner", "outer", "xmin" (x = 0), "ymin", "zmin".
struct SphereCavityOctantSpec {
  double inner_radius = 0.5;  ///< m, > 0
  double outer_radius = 2.0;  ///< m, > inner_radius
  Index zones_radial = 8;     ///< >= 1
  Index zones_around = 4;     ///< >= 1, zones along each patch edge
  double grading_ratio = 1.0; ///< Δr_{k+1}/Δr_k counting outwards
  double max_aspect_ratio = kDefaultMaxAspectRatio;
};

[[nodiscard]] Mesh make_box(const BoxSpec& spec);
[[nodiscard]] Mesh make_cylinder_cavity(const CylinderCavitySpec& spec);
[[nodiscard]] Mesh make_sphere_cavity_octant(const SphereCavityOctantSpec& spec);

/// Radii of the radial gridpoint rings of `spec` (zones_radial + 1 values, first
/// = inner radius, last = outer radius exactly).
[[nodiscard]] std::vector<double> graded_radii(const CylinderCavitySpec& spec);

/// What is wrong with a cavity floor: the scenario key to change (cavity_floor_z_m,
/// angle_deg or zones_around) and why.
struct CavityFloorProblem {
  std::string key;
  std::string message;
};

/// The first problem of spec.cavity_floor_z (outside the body, off the zone
/// levels, on a sector, zones_around not a multiple of 4); none without a floor.
[[nodiscard]] std::optional<CavityFloorProblem> cavity_floor_problem(const CylinderCavitySpec& spec);

/// The gridpoint level k (1 .. zones_vertical - 1) of spec.cavity_floor_z, the
/// layers being uniform (z_bottom + k height / zones_vertical); 0 without a
/// floor. Throws dfc::UserError with cavity_floor_problem's message.
[[nodiscard]] Index cavity_floor_level(const CylinderCavitySpec& spec);

}  // namespace dfc::fdm
