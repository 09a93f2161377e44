#include "dfc/dem/wall_forces.hpp"

#include <algorithm>

namespace dfc::dem {

void clear_wall_forces(Wall& wall) {
  std::fill(wall.vertex_force.begin(), wall.vertex_force.end(), Vec3{});
  wall.force = wall.moment = wall.force_on_particles = Vec3{};
  std::fill(wall.facet_force.begin(), wall.facet_force.end(), Vec3{});
}

void add_wall_contact(Wall& wall, std::uint32_t facet, const std::array<double, 3>& weights, const Vec3& on_particle, const Vec3& point,
                      const Vec3* couple) {
  if (on_particle == Vec3{} && (couple == nullptr || *couple == Vec3{})) return;
  const Vec3 on_wall = -on_particle;  // Newton's third law
  const Facet& f = wall.facets[facet];
  for (std::size_t v = 0; v < 3; ++v) wall.vertex_force[f[v]] += weights[v] * on_wall;
  wall.force += on_wall;
  if (!wall.facet_force.empty()) wall.facet_force[facet] += on_wall;
  wall.moment += cross(point, on_wall);
  if (couple != nullptr) wall.moment -= *couple;
  wall.force_on_particles += on_particle;
}

void distribute_wall_forces(Wall& wall, const WallContacts& contacts, const ContactOutputs& out, std::size_t offset) {
  clear_wall_forces(wall);
  const bool with_couple = !out.couple.empty();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const std::size_t o = offset + k;
    add_wall_contact(wall, contacts.facet[k], contacts.weights[k], out.force[o], out.point[o], with_couple ? &out.couple[o] : nullptr);
  }
}

}  // namespace dfc::dem
