#pragma once
// Geometry of sphere–facet contacts, independent of the contact law.
//
// A sphere near a shared edge or vertex of a mesh finds the same closest point
// on every facet around it, and a sphere resting on one facet of a flat mesh
// also finds the shared edges of its neighbours within reach: counting all of
// them would multiply the force. The rule used here keeps, for every particle
// and wall, one contact per locally-nearest surface feature:
//
//   a face contact is always kept;
//   an edge or vertex contact X on facet F is dropped if another candidate
//   facet G that contains X is at least as close (G's own closest point is
//   then nearer than X, or is X itself: a duplicate), ties going to faces,
//   then edges, then the lower facet index.
//
// This reproduces the edge/vertex de-duplication of triangle-mesh DEM walls
// (Kremmer & Favier 2001; LIGGGHTS mesh walls) without stored topology: shared
// vertices are recognised by their index. Every facet that contains X is a
// candidate whenever X is within reach, so the rule needs nothing outside
// the particle's group.
//
// A contact's history (its stored shear force, ...) is kept per facet. A
// sphere that slides or rolls across a shared edge, from facet A onto its
// neighbour B, is still the same contact: B takes over A's history in the
// step its selection moves. Then a flat wall behaves the same however it is
// cut into triangles; otherwise the shear force would drop to zero at every
// internal edge: on the diagonal of each plane wall, and between the facets
// of a pile.
#include <cstddef>
#include <span>

#include "dfc/dem/contact_lists.hpp"
#include "dfc/dem/particle_store.hpp"
#include "dfc/dem/wall.hpp"

namespace dfc::dem {

/// Fills weights, distance, feature and selected of every candidate of
/// `wall`, and the contact point into `points` (size contacts.size()); moves
/// the history of a contact that changed facets to its new facet.
void select_wall_contacts(const Wall& wall, const ParticleStore& particles, WallContacts& contacts, std::span<Vec3> points, int threads);

}  // namespace dfc::dem
