// Closest point on a triangle (Ericson 2005 §5.1.5): region, point, weights.
#include <gtest/gtest.h>

#include "dfc/dem/triangle_geometry.hpp"

namespace dfc::dem {
namespace {

const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};

void expect_point(const ClosestPoint& cp, Vec3 expected) {
  EXPECT_NEAR(cp.point.x, expected.x, 1e-15);
  EXPECT_NEAR(cp.point.y, expected.y, 1e-15);
  EXPECT_NEAR(cp.point.z, expected.z, 1e-15);
  EXPECT_NEAR(cp.weights[0] + cp.weights[1] + cp.weights[2], 1.0, 1e-15);
}

TEST(TriangleGeometry, AboveTheFaceProjectsWithBarycentricWeights) {
  const ClosestPoint cp = closest_point_on_triangle({0.2, 0.3, 0.7}, a, b, c);
  EXPECT_EQ(cp.feature, TriangleFeature::face);
  expect_point(cp, {0.2, 0.3, 0});
  EXPECT_NEAR(cp.weights[0], 0.5, 1e-15);
  EXPECT_NEAR(cp.weights[1], 0.2, 1e-15);
  EXPECT_NEAR(cp.weights[2], 0.3, 1e-15);
}

TEST(TriangleGeometry, OutsideAnEdgeProjectsOntoTheEdge) {
  const ClosestPoint ab = closest_point_on_triangle({0.4, -0.5, 0.1}, a, b, c);
  EXPECT_EQ(ab.feature, TriangleFeature::edge_ab);
  expect_point(ab, {0.4, 0, 0});
  const ClosestPoint bc = closest_point_on_triangle({0.8, 0.8, -0.2}, a, b, c);
  EXPECT_EQ(bc.feature, TriangleFeature::edge_bc);
  expect_point(bc, {0.5, 0.5, 0});
  EXPECT_EQ(bc.weights[0], 0.0);
}

TEST(TriangleGeometry, BeyondACornerIsTheVertex) {
  const ClosestPoint cp = closest_point_on_triangle({-0.3, -0.2, 0.4}, a, b, c);
  EXPECT_EQ(cp.feature, TriangleFeature::vertex_a);
  expect_point(cp, a);
  EXPECT_EQ(closest_point_on_triangle({2.0, -0.1, 0}, a, b, c).feature, TriangleFeature::vertex_b);
  EXPECT_EQ(closest_point_on_triangle({-0.1, 3.0, 1}, a, b, c).feature, TriangleFeature::vertex_c);
}

}  // namespace
}  // namespace dfc::dem
