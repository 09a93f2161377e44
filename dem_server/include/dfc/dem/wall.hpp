#pragma once
// Walls: triangle meshes the particles touch (docs/theory/coupling.md §2).
//
// Two kinds of motion share one representation, per-vertex velocities:
//   coupling   - vertices are continuum gridpoints; their velocities are given
//                at every exchange (x_vertex += v dt each step);
//   prescribed - a rigid wall (plane, platen, pile) translating at a fixed
//                velocity from a given step on.
// Each step a wall collects the force and moment the particles exert on it and
// the force on every vertex (barycentric distribution, wall_forces.hpp).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "dfc/dem/contact_law_registry.hpp"
#include "dfc/dem/vec3.hpp"

namespace dfc::dem {

using Facet = std::array<std::uint32_t, 3>;  ///< vertex indices within the wall

struct WallMesh {
  std::vector<Vec3> vertices;  ///< m
  std::vector<Facet> facets;   ///< shared vertices must share indices (the edge rules of wall_contacts rely on it)
};

/// Throws UserError naming `what` for an empty mesh, an index out of range,
/// a non-finite coordinate or a zero-area facet.
void validate_mesh(const WallMesh& mesh, const std::string& what);

enum class WallMotion { prescribed, coupling };

struct Wall {
  std::string name;
  WallMotion motion = WallMotion::prescribed;
  Vec3 prescribed_velocity;    ///< m/s, prescribed walls
  std::int64_t start_step = 0; ///< prescribed walls rest before this step
  ContactLawSetting law;       ///< the law of particle–facet contacts on this wall

  std::vector<Vec3> vertices;         ///< m, current positions
  std::vector<Vec3> vertex_velocity;  ///< m/s, during the current step
  std::vector<Facet> facets;

  // Results of the last step: what the particles exert ON the wall.
  std::vector<Vec3> vertex_force;  ///< N, per vertex (barycentric share of every contact force)
  Vec3 force;                      ///< N, sum over contacts
  Vec3 moment;                     ///< N m, about the global origin
  Vec3 force_on_particles;         ///< N, sum of the contact forces ON particles, summed on the particle side (= -force)
  /// N, per facet, ON the wall; kept only where sized to the facet count
  /// (the pile: its tip and shaft forces, foundation_loading.hpp), empty otherwise.
  std::vector<Vec3> facet_force;

  [[nodiscard]] std::size_t vertex_count() const noexcept { return vertices.size(); }
  [[nodiscard]] std::size_t facet_count() const noexcept { return facets.size(); }
};

/// A wall at rest with all result fields sized; validates the mesh.
[[nodiscard]] Wall make_wall(std::string name, WallMesh mesh, WallMotion motion, ContactLawSetting law, Vec3 velocity = {},
                             std::int64_t start_step = 0);

/// A sphere that overlaps a wall by at most this fraction of its radius is in
/// contact with it, not cut by it: a packing settled against a wall (e.g. the
/// peer benchmark's, whose bottom layer rests up to 31 nm, 6e-5 R, into its
/// floor) keeps its bottom layer and its initial contact forces.
inline constexpr double wall_contact_overlap_fraction = 1e-3;

/// True if the sphere overlaps a facet of `wall` by more than `fraction` of its
/// radius (generated spheres that would start with a large wall force).
[[nodiscard]] bool cut_by_wall(const Vec3& centre, double radius, const Wall& wall, double fraction = wall_contact_overlap_fraction);

}  // namespace dfc::dem
