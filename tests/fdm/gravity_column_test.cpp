// 1-D soil column under gravity (docs/theory/fdm.md §2(c)): the geostatic initial
// stress is the discrete equilibrium. (The column run to equilibrium from a
// stress-free start is the verification problem "gravity_column",
// fdm_server/verification, run by the CTest fdm_verification.gravity_column.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "dfc/fdm/initial_stress.hpp"
#include "dfc/fdm/mesh_generators.hpp"
#include "fdm_test_support.hpp"

namespace dfc::fdm {
namespace {

constexpr double kHeight = 10.0;
constexpr double kDensity = 2000.0;
constexpr double kGravity = 9.81;
constexpr double kYoung = 5.0e7;
constexpr double kPoisson = 0.3;
constexpr Index kZonesVertical = 21;  // odd: the middle zone's centroid is at mid-depth

Solver gravity_column(bool mass_scaling = true) {
  SolverSettings settings = test::quiet_settings(Vec3(0.0, 0.0, -kGravity));
  settings.mass_scaling = mass_scaling;
  Solver solver(make_box({Vec3::Zero(), Vec3(1.0, 1.0, kHeight), {1, 1, kZonesVertical}}),
                test::elastic_material(kYoung, kPoisson, kDensity), settings);
  for (const char* side : {"xmin", "xmax", "ymin", "ymax"}) solver.apply_boundary_condition({side, BoundaryKind::roller});
  solver.apply_boundary_condition({"zmin", BoundaryKind::fixed});
  return solver;
}

TEST(GravityColumn, GeostaticInitialStressStartsInEquilibrium) {
  Solver solver = gravity_column();
  const double k0 = kPoisson / (1.0 - kPoisson);
  solver.set_initial_stress([&](const Vec3& c) { return geostatic_stress({k0, kHeight}, kDensity, kGravity, c.z()); });
  solver.step(1.0);
  // The zone-centroid profile is the discrete equilibrium (§2(c)): the ratio is
  // round-off (1e-16 × number of summed terms), far below 1e-12.
  EXPECT_LT(solver.unbalanced_force_ratio(), 1e-12);
  for (int i = 0; i < 100; ++i) solver.step(1.0);
  double largest = 0.0;
  for (const Vec3& u : solver.displacements()) largest = std::max(largest, u.norm());
  EXPECT_LT(largest, 1e-12 * kHeight);
}

}  // namespace
}  // namespace dfc::fdm
