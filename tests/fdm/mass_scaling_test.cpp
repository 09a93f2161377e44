// Density scaling and the timestep limit (docs/theory/fdm.md §1.10).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "dfc/common/errors.hpp"

#include "dfc/fdm/mesh_generators.hpp"
#include "fdm_test_support.hpp"

namespace dfc::fdm {
namespace {

constexpr double kHeight = 4.0;
constexpr double kDensity = 2000.0;
constexpr double kGravity = 9.81;

Solver column(bool mass_scaling) {
  SolverSettings settings = test::quiet_settings(Vec3(0.0, 0.0, -kGravity));
  settings.mass_scaling = mass_scaling;
  Solver solver(make_box({Vec3::Zero(), Vec3(1.0, 1.0, kHeight), {2, 2, 8}}), test::elastic_material(3.0e7, 0.25, kDensity), settings);
  for (const char* side : {"xmin", "xmax", "ymin", "ymax"}) solver.apply_boundary_condition({side, BoundaryKind::roller});
  solver.apply_boundary_condition({"zmin", BoundaryKind::fixed});
  return solver;
}

double worst_vertical_stress_error(const Solver& solver) {
  double worst = 0.0;
  for (Index z = 0; z < solver.mesh().zone_count(); ++z) {
    const double vertical = kDensity * kGravity * (kHeight - solver.mesh().zone_centroid(z).z());
    worst = std::max(worst, std::abs(-solver.zone_stress(z).zz - vertical) / vertical);
  }
  return worst;
}

TEST(MassScaling, StepFarAboveCriticalStaysStableAndConverges) {
  Solver solver = column(true);
  const double dt = 1000.0 * solver.critical_timestep();
  const int steps = test::run_to_equilibrium(solver, dt, 1e-5, 20000);
  ASSERT_GT(steps, 0) << "did not converge";
  std::printf("[ mass scaling ] dt = 1000 x critical: ufr < 1e-5 after %d steps, worst sigma_v error %.2e\n", steps,
              worst_vertical_stress_error(solver));
  // At ufr 1e-5 the stress is within a fraction of a percent of ρ g d (§2(c)).
  EXPECT_LT(worst_vertical_stress_error(solver), 0.01);
  // The scaled inertial mass is what makes the step stable: it exceeds the real one.
  EXPECT_GT(solver.inertial_mass(0, dt), 100.0 * solver.real_mass(0));
}

TEST(MassScaling, WithoutScalingAStepAboveCriticalIsRefused) {
  Solver solver = column(false);
  const double critical = solver.critical_timestep();
  try {
    solver.step(1.5 * critical);
    FAIL() << "a step above the critical one was accepted";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("critical"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(solver.step(critical));
}

TEST(MassScaling, RealMassesAtTheCriticalStepStayStable) {
  Solver solver = column(false);
  const double dt = solver.critical_timestep();
  // Real masses at Δt_crit/2 (§1.10): with damping the column must settle, not
  // blow up. An unstable scheme grows by orders of magnitude within 100s of steps.
  const int steps = test::run_to_equilibrium(solver, dt, 1e-5, 60000);
  ASSERT_GT(steps, 0);
  std::printf("[ mass scaling ] real masses at dt_crit: ufr < 1e-5 after %d steps\n", steps);
  EXPECT_LT(worst_vertical_stress_error(solver), 0.01);
}

}  // namespace
}  // namespace dfc::fdm
