#pragma once
// From contact forces to wall loads: each contact's force on the wall goes to
// the facet's three vertices in proportion to the barycentric weights of the
// contact point (the PFC–FLAC3D wall–zone coupling, docs/theory/coupling.md §2). The weights
// sum to one, so the vertex forces sum to the contact force, and since
// sum_k w_k x_k = contact point they also carry its moment about any point.
#include <array>
#include <cstddef>
#include <cstdint>

#include "dfc/dem/contact_lists.hpp"
#include "dfc/dem/wall.hpp"

namespace dfc::dem {

/// Recomputes wall.vertex_force, force, moment and force_on_particles from the
/// contacts' outputs at [offset, offset + contacts.size()). Serial, in
/// contact order: reproducible.
void distribute_wall_forces(Wall& wall, const WallContacts& contacts, const ContactOutputs& out, std::size_t offset);

/// The two halves of distribute_wall_forces, for a caller that has the
/// contacts in another form (a decomposed run gathers them from its
/// processes, distributed_simulation.hpp): zero the results, then add each
/// contact in order. `couple` may be null (no law with a couple).
void clear_wall_forces(Wall& wall);
void add_wall_contact(Wall& wall, std::uint32_t facet, const std::array<double, 3>& weights, const Vec3& on_particle, const Vec3& point,
                      const Vec3* couple);

}  // namespace dfc::dem
