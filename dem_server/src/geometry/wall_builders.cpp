#include "dfc/dem/wall_builders.hpp"

#include <cmath>
#include <numbers>

#include "dfc/common/errors.hpp"

namespace dfc::dem {

WallMesh make_plane_mesh(const Vec3& point, const Vec3& normal, double half_size) {
  const double length = norm(normal);
  if (!(length > 0.0)) throw UserError("a plane wall needs a non-zero normal vector");
  if (!(half_size > 0.0)) throw UserError("a plane wall needs a positive half size");
  const Vec3 n = (1.0 / length) * normal;
  // In-plane basis: cross n with the coordinate axis least aligned with it.
  const Vec3 helper = std::abs(n.x) <= std::abs(n.y) && std::abs(n.x) <= std::abs(n.z) ? Vec3{1, 0, 0}
                      : std::abs(n.y) <= std::abs(n.z)                                  ? Vec3{0, 1, 0}
                                                                                        : Vec3{0, 0, 1};
  Vec3 u = cross(helper, n);
  u *= 1.0 / norm(u);
  const Vec3 v = cross(n, u);  // (u, v, n) right-handed
  WallMesh mesh;
  mesh.vertices = {point - half_size * u - half_size * v, point + half_size * u - half_size * v, point + half_size * u + half_size * v,
                   point - half_size * u + half_size * v};
  mesh.facets = {{0, 1, 2}, {0, 2, 3}};  // (u x v) = n: right-hand normal along n
  return mesh;
}

WallMesh make_closed_cylinder_mesh(const CylinderGeometry& g) {
  if (!(g.radius > 0.0) || !(g.length > 0.0)) throw UserError("a cylinder wall needs a positive radius and length");
  if (g.sides < 3) throw UserError("a cylinder wall needs at least 3 sides");
  const auto s = static_cast<std::uint32_t>(g.sides);
  WallMesh mesh;
  mesh.vertices.reserve(2 * s + 2);
  for (int ring = 0; ring < 2; ++ring)
    for (std::uint32_t k = 0; k < s; ++k) {
      const double theta = 2.0 * std::numbers::pi * double(k) / double(s);
      mesh.vertices.push_back({g.axis_x + g.radius * std::cos(theta), g.axis_y + g.radius * std::sin(theta), g.tip_z + ring * g.length});
    }
  const std::uint32_t bottom_centre = 2 * s;
  const std::uint32_t top_centre = 2 * s + 1;
  mesh.vertices.push_back({g.axis_x, g.axis_y, g.tip_z});
  mesh.vertices.push_back({g.axis_x, g.axis_y, g.tip_z + g.length});
  // The flat tip first: a contact on its rim edge (or a rim vertex) is a tie
  // between a tip facet and a side facet, and ties go to the lower facet index
  // (select_wall_contacts), so the tip owns its rim (the tip force of
  // foundation_loading.hpp includes the edge that leads the motion).
  for (std::uint32_t k = 0; k < s; ++k) mesh.facets.push_back({bottom_centre, (k + 1) % s, k});  // flat tip, normal -z
  for (std::uint32_t k = 0; k < s; ++k) {
    const std::uint32_t next = (k + 1) % s;
    const std::uint32_t b0 = k, b1 = next, t0 = s + k, t1 = s + next;
    mesh.facets.push_back({b0, b1, t1});  // side panel, outward normal
    mesh.facets.push_back({b0, t1, t0});
    mesh.facets.push_back({top_centre, t0, t1});  // top, normal +z
  }
  return mesh;
}

WallMesh make_open_tube_mesh(const CylinderGeometry& g) {
  if (!(g.radius > 0.0) || !(g.length > 0.0)) throw UserError("a tube wall needs a positive radius and length");
  if (!(g.inner_radius > 0.0 && g.inner_radius < g.radius)) throw UserError("a tube wall needs an inner radius between 0 and its radius");
  if (g.sides < 3) throw UserError("a tube wall needs at least 3 sides");
  const auto s = static_cast<std::uint32_t>(g.sides);
  // Rings: 0 outer at the tip, 1 inner at the tip, 2 outer at the top, 3 inner at the top.
  WallMesh mesh;
  mesh.vertices.reserve(4 * s);
  for (int ring = 0; ring < 4; ++ring) {
    const double r = ring % 2 == 0 ? g.radius : g.inner_radius;
    const double z = g.tip_z + (ring < 2 ? 0.0 : g.length);
    for (std::uint32_t k = 0; k < s; ++k) {
      const double theta = 2.0 * std::numbers::pi * double(k) / double(s);
      mesh.vertices.push_back({g.axis_x + r * std::cos(theta), g.axis_y + r * std::sin(theta), z});
    }
  }
  const auto at = [s](std::uint32_t ring, std::uint32_t k) { return ring * s + k % s; };
  for (std::uint32_t k = 0; k < s; ++k) {  // the annulus, normal -z
    mesh.facets.push_back({at(0, k), at(1, k), at(1, k + 1)});
    mesh.facets.push_back({at(0, k), at(1, k + 1), at(0, k + 1)});
  }
  for (std::uint32_t k = 0; k < s; ++k) {  // the inner shaft, normal towards the axis
    mesh.facets.push_back({at(1, k), at(3, k + 1), at(1, k + 1)});
    mesh.facets.push_back({at(1, k), at(3, k), at(3, k + 1)});
  }
  for (std::uint32_t k = 0; k < s; ++k) {  // the outer shaft, outward normal
    mesh.facets.push_back({at(0, k), at(0, k + 1), at(2, k + 1)});
    mesh.facets.push_back({at(0, k), at(2, k + 1), at(2, k)});
  }
  return mesh;
}

WallMesh make_pile_mesh(const CylinderGeometry& g) { return g.inner_radius > 0.0 ? make_open_tube_mesh(g) : make_closed_cylinder_mesh(g); }

}  // namespace dfc::dem
