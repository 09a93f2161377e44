// Sphere–facet contacts: normal and overlap on a face, an edge and a vertex;
// barycentric distribution of the force to the facet's vertices (docs/theory/coupling.md §2);
// one contact per surface feature on meshes with shared edges and vertices;
// the contact's history carried onto the next facet when the sphere crosses
// an internal edge.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/dem/wall_builders.hpp"

namespace dfc::dem {
namespace {

constexpr double r = 1e-3, rho = 2650.0, kn = 1e5, overlap = 1e-5;

/// One step of negligible length: the forces of the initial configuration.
Simulation touch(WallMesh mesh, Vec3 centre) {
  const ContactLawSetting law = test::linear(kn, kn, 0.5);
  Simulation sim = test::undamped(law);
  sim.add_wall(make_wall("w", std::move(mesh), WallMotion::prescribed, law));
  sim.add_sphere(0, centre, r, rho);
  sim.step(1e-12);
  return sim;
}

WallMesh triangle() { return {{{0, 0, 0}, {1e-2, 0, 0}, {0, 1e-2, 0}}, {{0, 1, 2}}}; }

/// Checks force = k_n overlap along `direction` (unit, from the wall to the
/// centre), and that the vertex forces sum to the wall's force and carry its
/// moment about vertex 0.
void check_contact(const Simulation& sim, Vec3 direction) {
  const Vec3 f = sim.particles().force[0];
  // |F| = k_n (r - d): the overlap comes from a distance, so ~1e-16 m / 1e-5 m rounding.
  EXPECT_NEAR(norm(f), kn * overlap, 1e-9 * kn * overlap);
  EXPECT_NEAR(dot(f, direction), norm(f), 1e-9 * norm(f));

  const Wall& wall = sim.walls()[0];
  Vec3 sum, moment_about_a;
  for (std::size_t v = 0; v < wall.vertex_count(); ++v) {
    sum += wall.vertex_force[v];
    moment_about_a += cross(wall.vertices[v] - wall.vertices[0], wall.vertex_force[v]);
  }
  // Weights sum to 1: equal to rounding (a few ulps of |F|).
  EXPECT_NEAR(norm(sum + f), 0.0, 1e-15 * norm(f));
  const Vec3 point = sim.contact_outputs().point[sim.wall_output_offset(0)];
  const Vec3 expected = cross(point - wall.vertices[0], -f);
  // sum_k w_k x_k = contact point, so the moments agree to rounding of |x||F|.
  EXPECT_NEAR(norm(moment_about_a - expected), 0.0, 1e-15 * 1e-2 * norm(f));
}

TEST(WallContact, OnTheFaceThePushIsAlongTheFacetNormal) {
  check_contact(touch(triangle(), {3e-3, 2e-3, r - overlap}), {0, 0, 1});
}

TEST(WallContact, OnAnEdgeThePushIsFromTheEdgeToTheCentre) {
  const Vec3 dir{0.0, -std::sqrt(0.5), std::sqrt(0.5)};
  check_contact(touch(triangle(), Vec3{4e-3, 0, 0} + (r - overlap) * dir), dir);
}

TEST(WallContact, AtAVertexThePushIsFromTheVertexToTheCentre) {
  const Vec3 dir = (1.0 / std::sqrt(6.0)) * Vec3{-1, 2, 1};
  check_contact(touch(triangle(), Vec3{0, 1e-2, 0} + (r - overlap) * dir), dir);
}

TEST(WallContact, SharedDiagonalOfAFlatPlaneGivesOneContact) {
  // make_plane_mesh splits the square along y = x. Exactly above it, and just
  // beside it (where the other triangle sees the diagonal within reach), the
  // sphere must feel one contact of k_n overlap, straight up.
  for (const double offset : {0.0, 1e-4}) {
    const Simulation sim = touch(make_plane_mesh({0, 0, 0}, {0, 0, 1}, 0.02), {2e-3 + offset, 2e-3, r - overlap});
    const Vec3 f = sim.particles().force[0];
    EXPECT_NEAR(f.z, kn * overlap, 1e-9 * kn * overlap) << "offset " << offset;
    // A spurious edge contact would tilt the force by ~10 %; rounding of the
    // mesh coordinates leaves ~1e-14 of it.
    EXPECT_NEAR(f.x, 0.0, 1e-12 * kn * overlap);
    EXPECT_NEAR(f.y, 0.0, 1e-12 * kn * overlap);
  }
}

TEST(WallContact, PileTipCentreSharedBy24FacetsGivesOneContact) {
  const WallMesh pile = make_closed_cylinder_mesh({.axis_x = 0, .axis_y = 0, .tip_z = 0, .radius = 5e-3, .length = 2e-2, .sides = 24});
  for (const double offset : {0.0, 3e-4}) {
    const Simulation sim = touch(pile, {offset, 0.5 * offset, -(r - overlap)});
    const Vec3 f = sim.particles().force[0];
    EXPECT_NEAR(f.z, -kn * overlap, 1e-9 * kn * overlap) << "offset " << offset;
    EXPECT_NEAR(std::hypot(f.x, f.y), 0.0, 1e-12 * kn * overlap);
  }
}

constexpr double overlap_slide = 1e-5, travel = 2e-4, ks_slide = 1e3;

/// Slides a sphere pressed `overlap_slide` into `mesh` at `start` along the
/// unit `direction` (tangent to the wall there) by `distance`, in `steps` steps
/// of prescribed motion (a sphere so heavy that its contact forces move it
/// by ~1e-16 m a step; its velocities are set again before each step). Returns
/// the force on it along `direction` at the end.
double shear_after_slide(WallMesh mesh, Vec3 start, Vec3 direction, double distance, int steps) {
  constexpr double step = 1e-4, density = 1e15;
  const ContactLawSetting law = test::linear(kn, ks_slide, 0.5);
  Simulation sim = test::undamped(law);
  sim.add_wall(make_wall("w", std::move(mesh), WallMotion::prescribed, law));
  sim.add_sphere(0, start, r, density);
  const Vec3 velocity = (distance / (steps * step)) * direction;
  for (int s = 0; s < steps; ++s) {
    sim.particles_for_edit().velocity[0] = velocity;
    sim.particles_for_edit().angular_velocity[0] = {};  // the shear force's moment would roll it
    sim.step(step);
  }
  return dot(sim.particles().force[0], direction);
}

// A stuck sphere dragged by u along a wall carries the shear force k_s u
// against the motion, wherever it is on the wall: crossing the edge two facets
// share must not reset it (wall_contacts.hpp). Here the sphere crosses it
// halfway, so a reset would leave about half. The normal force (1 N) holds
// the 0.2 N shear well below mu F_n, and the normal does not turn, so the
// shear force is k_s times the sum of the steps' displacements: rounding
// (~1e-13 relative) apart, exact.
TEST(WallContact, ShearForceCarriesAcrossTheDiagonalOfAFlatPlane) {
  // make_plane_mesh's two triangles share the diagonal y = -x here.
  const double f = shear_after_slide(make_plane_mesh({0, 0, 0}, {0, 0, 1}, 0.02), {2e-3, -2e-3 - 0.5 * travel, r - overlap_slide}, {0, 1, 0},
                                     travel, 2000);
  EXPECT_NEAR(f, -ks_slide * travel, 1e-9 * ks_slide * travel);
}

TEST(WallContact, ShearForceCarriesAcrossTheDiagonalOfAPileFacet) {
  // The side panel between angles 0 and 15 degrees: its two triangles share
  // the diagonal from (0 deg, z = 0) to (15 deg, z = 20 mm), at mid height in
  // the panel's middle. The sphere slides along the axis across it.
  constexpr double radius = 5e-3, length = 2e-2;
  const WallMesh pile = make_closed_cylinder_mesh({.axis_x = 0, .axis_y = 0, .tip_z = 0, .radius = radius, .length = length, .sides = 24});
  const double half_angle = std::numbers::pi / 24.0;
  const double centre_distance = radius * std::cos(half_angle) + r - overlap_slide;
  const Vec3 start{centre_distance * std::cos(half_angle), centre_distance * std::sin(half_angle), 0.5 * length - 0.5 * travel};
  const double f = shear_after_slide(pile, start, {0, 0, 1}, travel, 2000);
  EXPECT_NEAR(f, -ks_slide * travel, 1e-9 * ks_slide * travel);
}

TEST(WallContact, ShearForceCarriesAcrossTheFacetsAroundThePileTipCentre) {
  // The flat tip is 24 triangles around its centre. Sliding under it along x,
  // 20 um beside the centre, the contact crosses about ten of their edges
  // within 0.2 mm, some within a few steps of each other.
  const WallMesh pile = make_closed_cylinder_mesh({.axis_x = 0, .axis_y = 0, .tip_z = 0, .radius = 5e-3, .length = 2e-2, .sides = 24});
  const double f = shear_after_slide(pile, {-0.5 * travel, 2e-5, -(r - overlap_slide)}, {1, 0, 0}, travel, 2000);
  EXPECT_NEAR(f, -ks_slide * travel, 1e-9 * ks_slide * travel);
}

}  // namespace
}  // namespace dfc::dem
