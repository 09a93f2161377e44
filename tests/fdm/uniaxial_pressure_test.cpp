// Elastic box under pressure on its top face (closed-form elasticity).
#include <gtest/gtest.h>

#include <cmath>

#include "dfc/fdm/mesh_generators.hpp"
#include "fdm_test_support.hpp"

namespace dfc::fdm {
namespace {

constexpr double kYoung = 1.0e7;
constexpr double kPoisson = 0.25;
constexpr double kPressure = 1.0e4;
const Vec3 kSize(1.0, 1.0, 2.0);

Solver pressed_box(const std::vector<std::string>& rollers) {
  Solver solver(make_box({Vec3::Zero(), kSize, {2, 2, 4}}), test::elastic_material(kYoung, kPoisson, 2000.0), test::quiet_settings());
  for (const auto& group : rollers) solver.apply_boundary_condition({group, BoundaryKind::roller});
  solver.apply_boundary_condition({"zmax", BoundaryKind::pressure, kPressure});
  return solver;
}

// Converged to ufr < 1e-10 the fields are exact to ~1e-9 relative (a uniform
// stress field is represented exactly); 1e-6 is the tolerance.
constexpr double kRelativeTolerance = 1e-6;

TEST(UniaxialPressure, ConfinedBoxMatchesOedometricSolution) {
  Solver solver = pressed_box({"xmin", "xmax", "ymin", "ymax", "zmin"});
  ASSERT_GT(test::run_to_equilibrium(solver, 1.0, 1e-10, 50000), 0);
  // 1-D strain: σzz = −p, σxx = σyy = −ν/(1−ν) p, εzz = −p/M, M = E(1−ν)/((1+ν)(1−2ν)).
  const double constrained = kYoung * (1.0 - kPoisson) / ((1.0 + kPoisson) * (1.0 - 2.0 * kPoisson));
  const double lateral = -kPoisson / (1.0 - kPoisson) * kPressure;
  for (Index z = 0; z < solver.mesh().zone_count(); ++z) {
    const Stress s = solver.zone_stress(z);
    EXPECT_NEAR(s.zz, -kPressure, kRelativeTolerance * kPressure);
    EXPECT_NEAR(s.xx, lateral, kRelativeTolerance * kPressure);
    EXPECT_NEAR(s.yy, lateral, kRelativeTolerance * kPressure);
  }
  const double top_settlement = -kPressure * kSize.z() / constrained;
  for (const Index gp : solver.mesh().face_group_gridpoints("zmax"))
    EXPECT_NEAR(solver.displacements()[gp].z(), top_settlement, kRelativeTolerance * std::abs(top_settlement));
}

TEST(UniaxialPressure, BoxOnSymmetryRollersMatchesUniaxialStress) {
  Solver solver = pressed_box({"xmin", "ymin", "zmin"});
  ASSERT_GT(test::run_to_equilibrium(solver, 1.0, 1e-10, 50000), 0);
  // Uniaxial stress: σzz = −p, σxx = σyy = 0, u_z(top) = −pH/E, u_x(xmax) = +ν p Lx/E.
  for (Index z = 0; z < solver.mesh().zone_count(); ++z) {
    const Stress s = solver.zone_stress(z);
    EXPECT_NEAR(s.zz, -kPressure, kRelativeTolerance * kPressure);
    EXPECT_NEAR(s.xx, 0.0, kRelativeTolerance * kPressure);
    EXPECT_NEAR(s.yy, 0.0, kRelativeTolerance * kPressure);
  }
  const double top = -kPressure * kSize.z() / kYoung;
  const double side = kPoisson * kPressure * kSize.x() / kYoung;
  for (const Index gp : solver.mesh().face_group_gridpoints("zmax"))
    EXPECT_NEAR(solver.displacements()[gp].z(), top, kRelativeTolerance * std::abs(top));
  for (const Index gp : solver.mesh().face_group_gridpoints("xmax"))
    EXPECT_NEAR(solver.displacements()[gp].x(), side, kRelativeTolerance * side);
}

}  // namespace
}  // namespace dfc::fdm
