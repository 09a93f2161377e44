#include "dfc/fdm/mesh.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "dfc/common/errors.hpp"

namespace dfc::fdm {

const std::vector<FaceQuad>& Mesh::face_group(std::string_view name) const {
  const auto it = face_groups.find(name);
  if (it == face_groups.end())
    throw UserError("unknown face group \"" + std::string(name) + "\"; this mesh has: " + face_group_names());
  return it->second;
}

std::string Mesh::face_group_names() const {
  std::string names;
  for (const auto& [name, faces] : face_groups) names += (names.empty() ? "\"" : ", \"") + name + "\"";
  return names;
}

std::vector<Index> Mesh::face_group_gridpoints(std::string_view name) const {
  std::vector<Index> gridpoints;
  for (const FaceQuad& face : face_group(name)) gridpoints.insert(gridpoints.end(), face.begin(), face.end());
  std::sort(gridpoints.begin(), gridpoints.end());
  gridpoints.erase(std::unique(gridpoints.begin(), gridpoints.end()), gridpoints.end());
  return gridpoints;
}

Vec3 Mesh::zone_centroid(Index zone) const {
  Vec3 sum = Vec3::Zero();
  for (const Index gp : zones[zone]) sum += points[gp];
  return sum / 8.0;
}

Vec3 Mesh::face_centroid(const FaceQuad& face) const {
  return (points[face[0]] + points[face[1]] + points[face[2]] + points[face[3]]) / 4.0;
}

double Mesh::size() const {
  if (points.empty()) return 0.0;
  Vec3 lo = points.front();
  Vec3 hi = points.front();
  for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return (hi - lo).norm();
}

double Mesh::min_z() const {
  double z = std::numeric_limits<double>::infinity();
  for (const Vec3& p : points) z = std::min(z, p.z());
  return z;
}

double Mesh::max_z() const {
  double z = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : points) z = std::max(z, p.z());
  return z;
}

Vec3 quad_area_vector(const Mesh& mesh, const FaceQuad& face) {
  const Vec3 d13 = mesh.points[face[2]] - mesh.points[face[0]];
  const Vec3 d24 = mesh.points[face[3]] - mesh.points[face[1]];
  return 0.5 * d13.cross(d24);
}

}  // namespace dfc::fdm
