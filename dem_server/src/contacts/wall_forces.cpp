#include "dfc/dem/wall_forces.hpp"

#include <algorithm>

namespace dfc::dem {

void distribute_wall_forces(Wall& wall, const WallContacts& contacts, const ContactOutputs& out, std::size_t offset) {
  std::fill(wall.vertex_force.begin(), wall.vertex_force.end(), Vec3{});
  wall.force = wall.moment = wall.force_on_particles = Vec3{};
  const bool per_facet = !wall.facet_force.empty();
  if (per_facet) std::fill(wall.facet_force.begin(), wall.facet_force.end(), Vec3{});
  const bool with_couple = !out.couple.empty();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const std::size_t o = offset + k;
    const Vec3 on_particle = out.force[o];
    if (on_particle == Vec3{} && (!with_couple || out.couple[o] == Vec3{})) continue;
    const Vec3 on_wall = -on_particle;  // Newton's third law
    const Facet& f = wall.facets[contacts.facet[k]];
    const auto& w = contacts.weights[k];
    for (std::size_t v = 0; v < 3; ++v) wall.vertex_force[f[v]] += w[v] * on_wall;
    wall.force += on_wall;
    if (per_facet) wall.facet_force[contacts.facet[k]] += on_wall;
    wall.moment += cross(out.point[o], on_wall);
    if (with_couple) wall.moment -= out.couple[o];
    wall.force_on_particles += on_particle;
  }
}

}  // namespace dfc::dem
