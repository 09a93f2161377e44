#pragma once
// Boundary conditions on face groups. FLAC fixes velocities, not displacements
// (docs/theory/fdm.md §1.8); loads are lumped to the face corners (§1.7).
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "dfc/fdm/mesh.hpp"

namespace dfc::fdm {

enum class BoundaryKind {
  fixed,     ///< all velocity components zero
  roller,    ///< normal velocity zero (axis-aligned plane, or radial on a cylinder about z)
  pressure,  ///< pressure p on the face, pushing into the body when p > 0
  traction,  ///< traction vector t (force per area) on the face
};

struct BoundaryCondition {
  std::string group;
  BoundaryKind kind = BoundaryKind::fixed;
  double pressure = 0.0;           ///< Pa, for BoundaryKind::pressure
  Vec3 traction = Vec3::Zero();    ///< Pa, for BoundaryKind::traction
};

/// What a roller on a face group constrains.
struct RollerConstraint {
  enum class Type { axis, radial } type = Type::axis;
  int axis = 0;  ///< for Type::axis: the Cartesian component kept at zero
};

/// A roller is defined for a planar group whose normal is a coordinate axis
/// (that velocity component is held at zero) and for a cylindrical group about
/// the z axis (radial velocity held at zero). nullopt for any other group.
[[nodiscard]] std::optional<RollerConstraint> classify_roller(const Mesh& mesh, std::string_view group);

/// Adds the lumped nodal forces of a pressure or traction condition to `loads`
/// (one per gridpoint): each quad gives F/4 to each corner, F = −p a_quad for a
/// pressure (a_quad outward vector area) and F = t |a_quad| for a traction.
void add_face_loads(const Mesh& mesh, const BoundaryCondition& condition, std::span<Vec3> loads);

}  // namespace dfc::fdm
