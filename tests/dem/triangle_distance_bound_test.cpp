// The facet search's cull (TriangleDistanceBound): a lower bound of the exact
// distance to a triangle that never rejects a point the exact test keeps.
#include <cmath>

#include <gtest/gtest.h>

#include "dfc/dem/portable_random.hpp"
#include "dfc/dem/triangle_distance_bound.hpp"
#include "dfc/dem/triangle_geometry.hpp"

namespace dfc::dem {
namespace {

Vec3 random_point(PortableRandom& random, double half) {
  return {random.uniform(-half, half), random.uniform(-half, half), random.uniform(-half, half)};
}

TEST(TriangleDistanceBound, NeverExceedsTheExactDistance) {
  PortableRandom random(17);
  for (int t = 0; t < 200; ++t) {
    // Every other triangle long and thin, as a pile's shaft facets (0.5 mm by 30 mm).
    const Vec3 a = random_point(random, 0.01);
    const Vec3 b = t % 2 == 0 ? a + Vec3{0, 0, 0.03} : random_point(random, 0.01);
    const Vec3 c = t % 2 == 0 ? a + Vec3{5e-4, 1e-4, 0.03} : random_point(random, 0.01);
    const TriangleDistanceBound bound(a, b, c);
    for (int k = 0; k < 500; ++k) {
      const Vec3 p = random_point(random, 0.03);
      const double exact = distance_to_triangle(p, a, b, c);
      // Exact arithmetic gives bound <= distance; both are a few roundings of
      // coordinates below 0.05 m (an ulp is 7e-18 m), so 1e-15 m covers them.
      ASSERT_LE(bound.lower_bound(p), exact + 1e-15) << "triangle " << t << ", point " << k;
    }
  }
}

TEST(TriangleDistanceBound, IsTheExactDistanceAboveTheFaceAndBesideAnEdge) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  const TriangleDistanceBound bound(a, b, c);
  EXPECT_NEAR(bound.lower_bound({0.2, 0.3, 0.7}), 0.7, 1e-15);   // above the face: the plane
  EXPECT_NEAR(bound.lower_bound({0.2, 0.3, -0.4}), 0.4, 1e-15);  // either side
  EXPECT_NEAR(bound.lower_bound({0.4, -0.5, 0.0}), 0.5, 1e-15);  // in the plane beside edge ab
  EXPECT_NEAR(bound.lower_bound({0.6, 0.6, 0.0}), std::sqrt(0.02), 1e-15);  // beside edge bc
  // Beyond a vertex the bound is below the distance (the nearest half-space's, 0.5 here).
  EXPECT_NEAR(bound.lower_bound({-0.5, -0.5, 0.0}), 0.5, 1e-15);
  EXPECT_LT(bound.lower_bound({-0.5, -0.5, 0.0}), distance_to_triangle({-0.5, -0.5, 0.0}, a, b, c));
}

TEST(TriangleDistanceBound, NeverCullsAPointTheExactTestKeeps) {
  // Points above the face (either side), beside an edge and beyond a vertex
  // of a shaft-like facet, with the reach a relative 1e-14 above their exact
  // distance (the test distance < reach keeps them): never culled. At the
  // distance itself or just below it, culling would be allowed.
  const Vec3 a{0.004, 0.0, 0.01}, b{0.004, 0.0, 0.04}, c{0.00398, 5.2e-4, 0.04};
  const TriangleDistanceBound bound(a, b, c);
  const Vec3 n = triangle_normal(a, b, c);
  const Vec3 out_of_edge_ab = cross(b - a, n);
  const Vec3 inside = (1.0 / 3.0) * (a + b + c);
  const Vec3 beside_edge = a + Vec3{0, 0, 0.015} + (1e-3 / norm(out_of_edge_ab)) * out_of_edge_ab;
  const Vec3 beyond_vertex = a - Vec3{0, 0, 1e-3};
  for (const Vec3& p : {inside + 7.3e-4 * n, inside - 7.3e-4 * n, beside_edge, beyond_vertex}) {
    const double distance = distance_to_triangle(p, a, b, c);
    const double keeping_reach = distance * (1.0 + 1e-14);
    ASSERT_TRUE(distance < keeping_reach);
    EXPECT_FALSE(bound.certainly_beyond(p, keeping_reach));
    EXPECT_FALSE(bound.certainly_beyond(p, distance));  // the margin: a tie is never culled either
  }
  // It does cull what is clearly out of reach: 2 mm off the face, 1 mm beside an edge.
  EXPECT_TRUE(bound.certainly_beyond(inside + 2e-3 * n, 7.3e-4));
  EXPECT_TRUE(bound.certainly_beyond(beside_edge, 7.3e-4));
  EXPECT_FALSE(bound.certainly_beyond(inside + 5e-4 * n, 7.3e-4));
}

TEST(TriangleDistanceBound, ADegenerateTriangleCullsNothing) {
  const TriangleDistanceBound bound({0, 0, 0}, {1, 0, 0}, {2, 0, 0});
  EXPECT_EQ(bound.lower_bound({0, 5, 0}), 0.0);
  EXPECT_FALSE(bound.certainly_beyond({0, 5, 0}, 1e-3));
  // A sliver (twice its area 1e-8 of its longest edge squared), whose normal
  // rounding could mislead the cull: nothing is culled either.
  const TriangleDistanceBound sliver({0, 0, 0}, {1, 0, 0}, {0.5, 1e-8, 0});
  EXPECT_EQ(sliver.lower_bound({0.5, 0, 3}), 0.0);
  EXPECT_FALSE(sliver.certainly_beyond({0.5, 0, 3}, 1e-3));
  // A shaft-like facet (0.5 mm by 30 mm, 0.017) is not a sliver: it culls.
  const TriangleDistanceBound shaft({0, 0, 0}, {0, 0, 0.03}, {5e-4, 0, 0.03});
  EXPECT_TRUE(shaft.certainly_beyond({2e-4, 5e-3, 0.02}, 1e-3));
}

}  // namespace
}  // namespace dfc::dem
