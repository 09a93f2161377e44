// The Bonet & Burton (1998) nodal average (docs/continuum_pile.md §3).
#include <gtest/gtest.h>

#include <vector>

#include "dfc/continuum/nodal_average.hpp"

namespace dfc::continuum {
namespace {

// Two triangles sharing the edge 1–2 of the unit square 0-1-3-2.
const std::vector<Triangle> kTriangles{{0, 1, 2}, {1, 3, 2}};

TEST(NodalAverage, UniformFieldIsUnchanged) {
  const std::vector<double> weights{1.0, 3.0};
  const std::vector<double> values{0.25, 0.25};
  const std::vector<double> averaged = nodal_average(kTriangles, 4, weights, values);
  EXPECT_DOUBLE_EQ(averaged[0], 0.25);
  EXPECT_DOUBLE_EQ(averaged[1], 0.25);
}

TEST(NodalAverage, SharedNodesTakeTheWeightedMeanAndTrianglesTheMeanOfTheirNodes) {
  const std::vector<double> weights{1.0, 3.0};
  const std::vector<double> values{1.0, 0.0};
  const std::vector<double> averaged = nodal_average(kTriangles, 4, weights, values);
  // Node 0 only in triangle 0 (1), nodes 1 and 2 shared (1·1 + 3·0)/4, node 3 only in triangle 1 (0).
  EXPECT_DOUBLE_EQ(averaged[0], (1.0 + 0.25 + 0.25) / 3.0);
  EXPECT_DOUBLE_EQ(averaged[1], (0.25 + 0.0 + 0.25) / 3.0);
}

}  // namespace
}  // namespace dfc::continuum
