#include "dfc/fdm/boundary_conditions.hpp"

#include <algorithm>
#include <cmath>

namespace dfc::fdm {

namespace {

// Normals of generated meshes are exact up to round-off; 1e-9 on the cosine
// (≈ 4e-5 rad) accepts those and rejects anything visibly tilted.
constexpr double kAlignmentTolerance = 1e-9;

std::optional<int> common_normal_axis(const Mesh& mesh, const std::vector<FaceQuad>& faces) {
  std::optional<int> axis;
  for (const FaceQuad& face : faces) {
    const Vec3 normal = quad_area_vector(mesh, face).normalized();
    Index component = 0;
    normal.cwiseAbs().maxCoeff(&component);
    if (std::abs(normal[Eigen::Index(component)]) < 1.0 - kAlignmentTolerance) return std::nullopt;
    if (axis && *axis != int(component)) return std::nullopt;
    axis = int(component);
  }
  return axis;
}

bool is_cylinder_about_z(const Mesh& mesh, const std::vector<FaceQuad>& faces) {
  return std::all_of(faces.begin(), faces.end(), [&](const FaceQuad& face) {
    const Vec3 normal = quad_area_vector(mesh, face).normalized();
    const Vec3 centre = mesh.face_centroid(face);
    const Vec3 radial(centre.x(), centre.y(), 0.0);
    if (radial.norm() == 0.0) return false;
    return std::abs(normal.dot(radial.normalized())) > 1.0 - kAlignmentTolerance;
  });
}

}  // namespace

std::optional<RollerConstraint> classify_roller(const Mesh& mesh, std::string_view group) {
  const std::vector<FaceQuad>& faces = mesh.face_group(group);
  if (faces.empty()) return std::nullopt;
  if (const auto axis = common_normal_axis(mesh, faces)) return RollerConstraint{RollerConstraint::Type::axis, *axis};
  if (is_cylinder_about_z(mesh, faces)) return RollerConstraint{RollerConstraint::Type::radial, 0};
  return std::nullopt;
}

void add_face_loads(const Mesh& mesh, const BoundaryCondition& condition, std::span<Vec3> loads) {
  for (const FaceQuad& face : mesh.face_group(condition.group)) {
    const Vec3 area = quad_area_vector(mesh, face);
    // §1.7: lumped t·A/4 per corner of a quadrilateral face. The outward area
    // vector makes a positive pressure push into the body.
    const Vec3 face_force = condition.kind == BoundaryKind::pressure ? Vec3(-condition.pressure * area) : Vec3(condition.traction * area.norm());
    for (const Index gp : face) loads[gp] += face_force / 4.0;
  }
}

}  // namespace dfc::fdm
