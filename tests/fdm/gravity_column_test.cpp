// 1-D soil column under gravity (fdm-physics.md §2(c)): laterally rollered,
// fixed base, run to equilibrium with local damping. Depth d is measured down
// from the top; compression positive in the closed form:
//   σv = ρ g d,  σh = K0 σv with K0 = ν/(1−ν),  u_z(top) = −ρ g H²/(2M).
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

struct ColumnErrors {
  double vertical_mid = 0.0;    // relative error of σv at mid-depth
  double horizontal_mid = 0.0;  // relative error of σh at mid-depth
  double vertical_worst = 0.0;  // over all zones
  double settlement = 0.0;      // relative error of the top settlement
};

ColumnErrors column_errors(const Solver& solver) {
  ColumnErrors errors;
  const double k0 = kPoisson / (1.0 - kPoisson);
  for (Index z = 0; z < solver.mesh().zone_count(); ++z) {
    // §2(c): compare at zone centroids, where the discrete solution is exact.
    const double depth = kHeight - solver.mesh().zone_centroid(z).z();
    const double vertical = kDensity * kGravity * depth;
    const Stress s = solver.zone_stress(z);
    const double vertical_error = std::abs(-s.zz - vertical) / vertical;
    errors.vertical_worst = std::max(errors.vertical_worst, vertical_error);
    if (std::abs(depth - kHeight / 2.0) < 1e-9) {
      errors.vertical_mid = vertical_error;
      errors.horizontal_mid = std::max(std::abs(-s.xx - k0 * vertical), std::abs(-s.yy - k0 * vertical)) / (k0 * vertical);
    }
  }
  const double constrained = kYoung * (1.0 - kPoisson) / ((1.0 + kPoisson) * (1.0 - 2.0 * kPoisson));
  const double top = -kDensity * kGravity * kHeight * kHeight / (2.0 * constrained);
  for (const Index gp : solver.mesh().face_group_gridpoints("zmax"))
    errors.settlement = std::max(errors.settlement, std::abs(solver.displacements()[gp].z() - top) / std::abs(top));
  return errors;
}

TEST(GravityColumn, ReachesK0StateWithinOnePercentAtMidDepth) {
  Solver solver = gravity_column();
  const int steps = test::run_to_equilibrium(solver, 1.0, 1e-6, 100000);
  ASSERT_GT(steps, 0) << "no equilibrium";
  const ColumnErrors e = column_errors(solver);
  std::printf("[ gravity column ] %d steps to ufr < 1e-6: sigma_v mid-depth error %.2e, sigma_h %.2e, worst zone %.2e, settlement %.2e\n",
              steps, e.vertical_mid, e.horizontal_mid, e.vertical_worst, e.settlement);
  // Required accuracy 1 % (fdm-physics.md §2 tolerances); lumped gravity makes the
  // centroid values exact, so what remains is the convergence error (ufr 1e-6).
  EXPECT_LT(e.vertical_mid, 0.01);
  EXPECT_LT(e.horizontal_mid, 0.01);
  EXPECT_LT(e.vertical_worst, 0.01);
  EXPECT_LT(e.settlement, 0.01);
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
