// The graded box, the cylinder sector and the spherical-shell octant (the
// verification meshes), and the zone-quality checks (aspect ratio, named zones).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dfc/common/errors.hpp"
#include "dfc/fdm/boundary_conditions.hpp"
#include "dfc/fdm/grading.hpp"
#include "dfc/fdm/hex_overlays.hpp"
#include "dfc/fdm/mesh_generators.hpp"
#include "dfc/fdm/mesh_quality.hpp"
#include "fdm_test_support.hpp"

namespace dfc::fdm {
namespace {

using test::mesh_volume;

TEST(Grading, GeometricSpacingHasExactEndsAndTheRequestedRatio) {
  const std::vector<double> x = geometric_spacing(-1.0, 2.0, 7, 1.3);
  ASSERT_EQ(x.size(), 8u);
  EXPECT_EQ(x.front(), -1.0);
  EXPECT_EQ(x.back(), 2.0);
  for (std::size_t k = 1; k + 1 < x.size(); ++k) EXPECT_NEAR((x[k + 1] - x[k]) / (x[k] - x[k - 1]), 1.3, 1e-12);
  const std::vector<double> u = geometric_spacing(0.0, 1.0, 4, 1.0);
  EXPECT_DOUBLE_EQ(u[1], 0.25);
}

TEST(BoxMesh, GradingKeepsTheBoxAndRefinesTowardsTheChosenSide) {
  const Mesh mesh = make_box({Vec3(0, 0, -2), Vec3(1, 2, 2), {4, 4, 5}, {1.5, 1.0, 1.0 / 1.5}});
  EXPECT_NEAR(mesh_volume(mesh), 4.0, 1e-12);
  // x: finer at xmin; z: finer at zmax.
  EXPECT_LT(mesh.points[1].x() - mesh.points[0].x(), mesh.points[4].x() - mesh.points[3].x());
  const Index layer = 5 * 5;
  EXPECT_GT(mesh.points[layer].z() - mesh.points[0].z(), mesh.points[5 * layer].z() - mesh.points[4 * layer].z());
  EXPECT_THROW((void)make_box({Vec3::Zero(), Vec3::Ones(), {2, 2, 2}, {1.0, 0.0, 1.0}}), UserError);
}

TEST(CylinderCavityMesh, QuarterSectorHasAxisAlignedSymmetrySidesAndTheSectorVolume) {
  CylinderCavitySpec spec;
  spec.inner_radius = 1.0;
  spec.outer_radius = 3.0;
  spec.zones_radial = 5;
  spec.zones_around = 6;
  spec.zones_vertical = 1;
  spec.height = 0.5;
  spec.angle_deg = 90.0;
  const Mesh mesh = make_cylinder_cavity(spec);
  EXPECT_EQ(mesh.gridpoint_count(), 6u * 7u * 2u);
  // Inscribed polygon: ¼ n sin(π/(2n))·… = the sector's polygonal area (n facets of angle π/2n).
  const double x = std::numbers::pi / 2.0 / 6.0;
  EXPECT_NEAR(mesh_volume(mesh), 0.5 * 6.0 * std::sin(x) * (9.0 - 1.0) * 0.5, 1e-12);
  const auto min_side = classify_roller(mesh, "theta_min");
  const auto max_side = classify_roller(mesh, "theta_max");
  ASSERT_TRUE(min_side && max_side);
  EXPECT_EQ(min_side->axis, 1);  // θ = 0: the plane y = 0
  EXPECT_EQ(max_side->axis, 0);  // θ = 90°: the plane x = 0
  for (const Index gp : mesh.face_group_gridpoints("theta_max")) EXPECT_EQ(mesh.points[gp].x(), 0.0);
}

TEST(SphereCavityOctantMesh, FillsTheOctantShellWithSharedPatchEdgesAndSymmetryGroups) {
  SphereCavityOctantSpec spec;
  spec.inner_radius = 1.0;
  spec.outer_radius = 2.0;
  spec.zones_radial = 3;
  spec.zones_around = 4;
  const Mesh mesh = make_sphere_cavity_octant(spec);
  EXPECT_EQ(mesh.zone_count(), 3u * 3u * 4u * 4u);
  // Gridpoints per radial layer: 3 patches of 5×5 minus the shared edges
  // (3 edges of 5 points, the centre counted once): 75 − 3·5 + 1 = 61.
  EXPECT_EQ(mesh.gridpoint_count(), 61u * 4u);
  // Faceted: the volume approaches the octant shell from below.
  const double shell = std::numbers::pi / 6.0 * (8.0 - 1.0);
  const double volume = mesh_volume(mesh);
  EXPECT_LT(volume, shell);
  EXPECT_GT(volume, 0.95 * shell);
  // Gridpoints on the spheres and on the symmetry planes.
  for (const Index gp : mesh.face_group_gridpoints("inner")) EXPECT_NEAR(mesh.points[gp].norm(), 1.0, 1e-14);
  for (const char* plane : {"xmin", "ymin", "zmin"}) {
    const auto roller = classify_roller(mesh, plane);
    ASSERT_TRUE(roller) << plane;
    EXPECT_EQ(roller->axis, plane[0] - 'x');
  }
  EXPECT_EQ(mesh.face_group("inner").size(), 3u * 16u);
  EXPECT_NO_THROW(check_mesh_quality(mesh));
}

TEST(MeshQuality, AspectRatioErrorNamesTheOffendingZones) {
  const Mesh mesh = make_box({Vec3::Zero(), Vec3(12.0, 1.0, 1.0), {1, 1, 1}});
  EXPECT_NEAR(zone_aspect_ratio(mesh, 0), 12.0, 1e-12);
  try {
    check_aspect_ratios(mesh, 10.0, "test mesh");
    FAIL() << "no error";
  } catch (const UserError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("zones 0 (centroid 6"), std::string::npos) << message;
    EXPECT_NE(message.find("max_aspect_ratio"), std::string::npos) << message;
  }
  // A cavity mesh too coarse around the circumference for its thickness is refused.
  CylinderCavitySpec coarse;
  coarse.inner_radius = 0.5;
  coarse.outer_radius = 0.6;
  coarse.zones_radial = 4;
  coarse.zones_around = 6;
  EXPECT_THROW((void)make_cylinder_cavity(coarse), UserError);
}

}  // namespace
}  // namespace dfc::fdm
