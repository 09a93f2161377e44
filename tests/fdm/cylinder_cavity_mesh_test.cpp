// The thick-walled cylinder mesh around the DEM cavity (docs/fdm_models.md).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dfc/fdm/hex_overlays.hpp"
#include "dfc/fdm/mesh_generators.hpp"
#include "fdm_test_support.hpp"

namespace dfc::fdm {
namespace {

CylinderCavitySpec spec() {
  CylinderCavitySpec s;
  s.inner_radius = 0.5;
  s.outer_radius = 2.0;
  s.z_bottom = -1.0;
  s.height = 1.5;
  s.zones_radial = 6;
  s.zones_around = 24;
  s.zones_vertical = 2;
  s.grading_ratio = 1.3;
  return s;
}

TEST(CylinderCavityMesh, VolumeMatchesAnnulusWithinFacetingError) {
  const CylinderCavitySpec s = spec();
  const Mesh mesh = make_cylinder_cavity(s);
  const double volume = test::mesh_volume(mesh);
  const double annulus = std::numbers::pi * (s.outer_radius * s.outer_radius - s.inner_radius * s.inner_radius) * s.height;
  // Gridpoints sit on the circles, so the walls are inscribed polygons: the
  // exact volume is that of the polygonal annulus, ½ n sin(2π/n)(Ro²−Ri²)H,
  // smaller than the annulus by the factor sin(x)/x, x = 2π/n.
  const double x = 2.0 * std::numbers::pi / double(s.zones_around);
  EXPECT_NEAR(volume, annulus * std::sin(x) / x, 1e-12 * annulus);
  const double faceting_error = 1.0 - std::sin(x) / x;  // ≈ x²/6 = 1.1 % for n = 24
  EXPECT_GT(annulus - volume, 0.0);
  EXPECT_LE((annulus - volume) / annulus, faceting_error + 1e-12);
  EXPECT_NO_THROW(check_mesh_quality(mesh));
}

TEST(CylinderCavityMesh, FaceNormalsPointOutOfTheBody) {
  const Mesh mesh = make_cylinder_cavity(spec());
  const auto radial = [&](const FaceQuad& f) {
    const Vec3 c = mesh.face_centroid(f);
    return Vec3(c.x(), c.y(), 0.0).normalized();
  };
  for (const FaceQuad& f : mesh.face_group("inner")) EXPECT_LT(quad_area_vector(mesh, f).normalized().dot(radial(f)), -0.999);  // towards the axis
  for (const FaceQuad& f : mesh.face_group("outer")) EXPECT_GT(quad_area_vector(mesh, f).normalized().dot(radial(f)), 0.999);
  for (const FaceQuad& f : mesh.face_group("top")) EXPECT_GT(quad_area_vector(mesh, f).normalized().z(), 0.999);
  for (const FaceQuad& f : mesh.face_group("bottom")) EXPECT_LT(quad_area_vector(mesh, f).normalized().z(), -0.999);
  EXPECT_EQ(mesh.face_group("inner").size(), 24u * 2u);
  EXPECT_EQ(mesh.face_group("top").size(), 24u * 6u);
}

TEST(CylinderCavityMesh, GradingRatioIsHonouredAndRadiiAreExactAtTheWalls) {
  const CylinderCavitySpec s = spec();
  const std::vector<double> radii = graded_radii(s);
  ASSERT_EQ(radii.size(), s.zones_radial + 1);
  EXPECT_DOUBLE_EQ(radii.front(), s.inner_radius);
  EXPECT_DOUBLE_EQ(radii.back(), s.outer_radius);
  // Δr_{k+1}/Δr_k = ratio (finer towards the cavity); 1e-12 = round-off of the partial sums.
  for (std::size_t k = 1; k + 1 < radii.size(); ++k)
    EXPECT_NEAR((radii[k + 1] - radii[k]) / (radii[k] - radii[k - 1]), s.grading_ratio, 1e-12);
  // The mesh places its rings there.
  const Mesh mesh = make_cylinder_cavity(s);
  for (std::size_t k = 0; k < radii.size(); ++k) EXPECT_NEAR(mesh.points[k].head<2>().norm(), radii[k], 1e-12);
}

TEST(CylinderCavityMesh, SeamHasNoDuplicateGridpoints) {
  const CylinderCavitySpec s = spec();
  const Mesh mesh = make_cylinder_cavity(s);
  EXPECT_EQ(mesh.gridpoint_count(), (s.zones_radial + 1) * s.zones_around * (s.zones_vertical + 1));
  double closest = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < mesh.points.size(); ++a)
    for (std::size_t b = a + 1; b < mesh.points.size(); ++b) closest = std::min(closest, (mesh.points[a] - mesh.points[b]).norm());
  EXPECT_GT(closest, 1e-3);
}

}  // namespace
}  // namespace dfc::fdm
