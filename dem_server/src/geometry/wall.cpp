#include "dfc/dem/wall.hpp"

#include "dfc/common/errors.hpp"
#include "dfc/dem/triangle_geometry.hpp"

namespace dfc::dem {

void validate_mesh(const WallMesh& mesh, const std::string& what) {
  if (mesh.facets.empty()) throw UserError(what + " has no facets; a wall needs at least one triangle");
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (!is_finite(mesh.vertices[v])) throw UserError(what + ": vertex " + std::to_string(v) + " has a non-finite coordinate");
  for (std::size_t f = 0; f < mesh.facets.size(); ++f) {
    for (const auto v : mesh.facets[f])
      if (v >= mesh.vertices.size())
        throw UserError(what + ": facet " + std::to_string(f) + " refers to vertex " + std::to_string(v) + " but there are only " +
                        std::to_string(mesh.vertices.size()) + " vertices");
    const auto& [a, b, c] = mesh.facets[f];
    if (norm2(cross(mesh.vertices[b] - mesh.vertices[a], mesh.vertices[c] - mesh.vertices[a])) == 0.0)
      throw UserError(what + ": facet " + std::to_string(f) + " has zero area (repeated or collinear vertices)");
  }
}

Wall make_wall(std::string name, WallMesh mesh, WallMotion motion, ContactLawSetting law, Vec3 velocity, std::int64_t start_step) {
  validate_mesh(mesh, "wall \"" + name + "\"");
  Wall wall;
  wall.name = std::move(name);
  wall.motion = motion;
  wall.prescribed_velocity = velocity;
  wall.start_step = start_step;
  wall.law = std::move(law);
  wall.vertices = std::move(mesh.vertices);
  wall.facets = std::move(mesh.facets);
  wall.vertex_velocity.assign(wall.vertices.size(), Vec3{});
  wall.vertex_force.assign(wall.vertices.size(), Vec3{});
  return wall;
}

bool cut_by_wall(const Vec3& centre, double radius, const Wall& wall, double fraction) {
  const double cut_distance = radius * (1.0 - fraction);
  for (const auto& f : wall.facets)
    if (distance_to_triangle(centre, wall.vertices[f[0]], wall.vertices[f[1]], wall.vertices[f[2]]) < cut_distance) return true;
  return false;
}

}  // namespace dfc::dem
