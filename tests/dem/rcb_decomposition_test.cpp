// RcbDecomposition (rcb_decomposition.hpp): weighted recursive coordinate
// bisection, the boxes of a decomposed DEM run.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "dfc/dem/portable_random.hpp"
#include "dfc/dem/rcb_decomposition.hpp"

namespace dfc::dem {
namespace {

std::vector<Vec3> random_points(std::size_t n, Vec3 extent, std::uint64_t seed) {
  PortableRandom random(seed);
  std::vector<Vec3> points(n);
  for (auto& x : points) x = {random.uniform(0, extent.x), random.uniform(0, extent.y), random.uniform(0, extent.z)};
  return points;
}

TEST(RcbDecomposition, EqualWeightsGiveEveryPartAboutTheSameCountAndEveryPointTheBoxThatHoldsIt) {
  const auto points = random_points(10000, {3, 1, 2}, 7);
  const std::vector<double> weights(points.size(), 1.0);
  for (int parts : {1, 2, 3, 5, 7, 16}) {
    const RcbDecomposition rcb(points, weights, parts);
    std::vector<std::size_t> count(std::size_t(parts), 0);
    for (const auto& x : points) {
      const int owner = rcb.owner(x);
      ASSERT_TRUE(rcb.box(owner).contains(x)) << parts << " parts";
      int holders = 0;
      for (int q = 0; q < parts; ++q) holders += rcb.box(q).contains(x) ? 1 : 0;
      ASSERT_EQ(holders, 1) << parts << " parts";
      ++count[std::size_t(owner)];
    }
    // Each cut puts the target weight within one point of it; the counts
    // of parts at depth log2(parts) differ by at most a few points.
    const auto [least, most] = std::minmax_element(count.begin(), count.end());
    EXPECT_LE(double(*most - *least), 4.0) << parts << " parts";
  }
}

TEST(RcbDecomposition, TheBoxesTileAllOfSpace) {
  const auto points = random_points(500, {1, 1, 1}, 3);
  const RcbDecomposition rcb(points, std::vector<double>(points.size(), 1.0), 6);
  // Far outside the points, and exactly on a cut (a box's finite corner): one box each.
  const auto on_cuts = [](Vec3 x) {
    const auto finite = [](double v) { return std::isfinite(v) ? v : 0.5; };
    return Vec3{finite(x.x), finite(x.y), finite(x.z)};
  };
  for (const Vec3& x : std::vector<Vec3>{{-1e9, 5, 0.5}, {1e9, -1e9, 1e9}, on_cuts(rcb.box(0).hi), on_cuts(rcb.box(5).lo)}) {
    int holders = 0;
    for (int q = 0; q < 6; ++q) holders += rcb.box(q).contains(x) ? 1 : 0;
    EXPECT_EQ(holders, 1);
    EXPECT_TRUE(rcb.box(rcb.owner(x)).contains(x));
  }
}

TEST(RcbDecomposition, WeightsMoveTheCutsTowardTheHeavyPoints) {
  // A fine zone (x < 1) with 12 times the weight per point of the coarse one.
  const auto points = random_points(4000, {2, 1, 1}, 5);
  std::vector<double> weights;
  for (const auto& x : points) weights.push_back(x.x < 1.0 ? 12.0 : 1.0);
  const RcbDecomposition rcb(points, weights, 2);
  std::vector<double> load(2, 0.0);
  for (std::size_t k = 0; k < points.size(); ++k) load[std::size_t(rcb.owner(points[k]))] += weights[k];
  EXPECT_NEAR(load[0] / load[1], 1.0, 0.02);  // one heavy point is 12 / ~26 000 of a part
  EXPECT_LT(rcb.box(0).hi.x, 0.6);            // the equal-weight cut sits near x = 13/24 = 0.54
}

TEST(RcbDecomposition, TheSameInputGivesTheSameBoxes) {
  const auto points = random_points(3000, {1, 2, 1}, 9);
  const std::vector<double> weights(points.size(), 1.0);
  const RcbDecomposition a(points, weights, 7), b(points, weights, 7);
  for (int q = 0; q < 7; ++q) {
    EXPECT_EQ(a.box(q).lo, b.box(q).lo);
    EXPECT_EQ(a.box(q).hi, b.box(q).hi);
  }
}

TEST(RcbDecomposition, DistanceToABoxIsZeroInsideAndEuclideanOutside) {
  const SpaceBox box{{0, 0, 0}, {1, 2, 3}};
  EXPECT_EQ(box.distance({0.5, 1, 1}), 0.0);
  EXPECT_DOUBLE_EQ(box.distance({2, 1, 1}), 1.0);
  EXPECT_DOUBLE_EQ(box.distance({-3, -4, 1}), 5.0);
}

}  // namespace
}  // namespace dfc::dem
