// A bed settled under gravity with local damping carries its weight on the floor.
#include <gtest/gtest.h>

#include "dem_test_support.hpp"

namespace dfc::dem {
namespace {

TEST(SettledBed, FloorCarriesTheTotalWeightAtRest) {
  Simulation sim = test::settled_box_bed().simulation;
  const double dt = test::settled_box_bed().dt;
  const Measurements m = measure(sim);
  RecordProperty("settle_steps", std::to_string(test::settled_box_bed().settle_steps));
  RecordProperty("unbalanced_force_ratio", test::figure(m.unbalanced_force_ratio));
  RecordProperty("coordination_number", test::figure(m.coordination_number));
  ASSERT_LT(m.unbalanced_force_ratio, 1e-4) << "the bed did not settle";
  Vec3 floor;
  const int n = 1000;
  for (int s = 0; s < n; ++s) {
    sim.step(dt);
    floor += sim.walls()[0].force;  // wall 0 is "floor"
  }
  floor *= 1.0 / n;
  // At rest (static equilibrium, local damping inactive) the floor reaction is
  // the weight: the side walls are frictionless. 0.5 % allows for the residual motion.
  EXPECT_NEAR(-floor.z, m.total_weight, 0.005 * m.total_weight);
  RecordProperty("floor_force_over_weight_minus_1", test::figure(-floor.z / m.total_weight - 1.0));
  EXPECT_GT(m.coordination_number, 3.0);  // a real packing, not loose spheres
}

}  // namespace
}  // namespace dfc::dem
