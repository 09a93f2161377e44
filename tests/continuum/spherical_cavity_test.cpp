// The spherical cavity on a meridian mesh (docs/continuum_pile.md §3, §7): a
// two-dimensional triangulation of a one-dimensional field, where
// constant-strain triangles lock when the material is nearly incompressible
// and the pressure projection must not; and its large-strain expansion in Tresca.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cavity_expansion.hpp"
#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/constitutive/mohr_coulomb_model.hpp"
#include "dfc/continuum/tresca_cavity_closed_form.hpp"

namespace dfc::continuum {
namespace {

constexpr double kInSitu = 200e3;

/// The test mesh (30 × 12, graded 1.1) or a coarser one with the same
/// grading over the same radii (20 × 8, 1.1^1.5): h × 1.5.
CavityMeshSpec sphere_mesh(Index radial_divisions) {
  CavityMeshSpec spec = test::spherical_test_mesh();
  if (radial_divisions == 20) {
    spec.radial_divisions = 20;
    spec.tangential_divisions = 8;
    spec.radial_ratio = std::pow(1.1, 1.5);
  }
  return spec;
}

struct ElasticSphere {
  double wall_error = 0.0;       ///< (Δp − Δp_Lamé)/Δp_Lamé at the wall
  double pressure_spread = 0.0;  ///< max over triangles |p − σ₀| / Δp_Lamé
  double unbalanced = 0.0;
};

// Elastic, ν = 0.4999 (K/G = 5000), a/a₀ = 1.001: Lamé's spherical cavity
// with the pressure σ₀ held at b (Timoshenko & Goodier 1970): the wall
// pressure rises by Δp = 4G (u/a)(1 − a³/b³) for an incompressible medium
// (ν = 0.4999 differs by O((1 − 2ν) a³/b³) = 3e-8), and the mean stress is σ₀
// everywhere (σ_rr + 2σ_θθ does not change), so any spread of the
// triangles' pressure is a spurious pressure mode.
ElasticSphere nearly_incompressible_sphere(Index radial_divisions, VolumetricStrain treatment) {
  const double poisson = 0.4999;
  const constitutive::ElasticModuli moduli = constitutive::moduli_from_young_poisson(2.0 * 1e7 * (1.0 + poisson), poisson);
  const CavityMeshSpec spec = sphere_mesh(radial_divisions);
  SolverSettings settings;
  settings.volumetric_strain = treatment;
  test::CavityExpansion cavity(test::CavityShape::spherical, spec, std::make_shared<constitutive::ElasticModel>(moduli), kInSitu, settings);
  cavity.expand_to(1.001, 20000);
  cavity.settle(20000);
  const double ratio = spec.inner_radius / spec.outer_radius;
  const double lame = 4.0 * moduli.shear * 1e-3 * (1.0 - ratio * ratio * ratio);
  ElasticSphere result;
  result.wall_error = (cavity.wall_pressure() - kInSitu - lame) / lame;
  for (const Stress& stress : cavity.solver().stresses())
    result.pressure_spread = std::max(result.pressure_spread, std::abs(-stress.trace() / 3.0 - kInSitu) / lame);
  result.unbalanced = cavity.solver().unbalanced_force_ratio();
  return result;
}

TEST(SphericalCavity, NearlyIncompressibleElasticWallPressureConvergesToLameWithThePressureProjection) {
  const ElasticSphere coarse = nearly_incompressible_sphere(20, VolumetricStrain::pressure_projection);
  const ElasticSphere fine = nearly_incompressible_sphere(30, VolumetricStrain::pressure_projection);
  std::printf("nu = 0.4999, pressure projection: wall pressure change error %+.2f %% (20 x 8), %+.2f %% (30 x 12); unbalanced %.1e\n",
              100.0 * coarse.wall_error, 100.0 * fine.wall_error, fine.unbalanced);
  // Measured −3.85 % and −1.87 % (−1.12 % on 40 × 16): of order h^1.8, the
  // discretisation of a 1/ρ³ field by linear triangles; the projection is
  // slightly soft. Bounds: the measured values with a margin of a third; the
  // small-strain closed form itself differs by O(u/a) = 0.1 %.
  EXPECT_NEAR(coarse.wall_error, 0.0, 0.05);
  EXPECT_NEAR(fine.wall_error, 0.0, 0.025);
  EXPECT_LT(std::abs(fine.wall_error), std::abs(coarse.wall_error));  // shrinks with refinement
}

TEST(SphericalCavity, NearlyIncompressiblePressureFieldIsUniformWithThePressureProjectionNotWithTheNodalAverage) {
  const ElasticSphere projected = nearly_incompressible_sphere(30, VolumetricStrain::pressure_projection);
  const ElasticSphere averaged = nearly_incompressible_sphere(30, VolumetricStrain::nodal_average);
  std::printf("nu = 0.4999, 30 x 12: max |p - s0| / dp_wall = %.3f with the projection, %.1f with the nodal average "
              "(wall errors %+.2f %%, %+.2f %%)\n",
              projected.pressure_spread, averaged.pressure_spread, 100.0 * projected.wall_error, 100.0 * averaged.wall_error);
  // Measured 0.059 with the projection (the largest next to the wall, where
  // the field varies fastest) against 46.9 with the nodal average: Bonet &
  // Burton's element, an unstabilised P1–P1 pair, carries a checkerboard 47
  // times the wall pressure change, and its wall pressure is +10.3 % off.
  EXPECT_LT(projected.pressure_spread, 0.1);
  EXPECT_GT(averaged.pressure_spread, 10.0);
  EXPECT_GT(averaged.wall_error, 0.05);
}

// Tresca (s_u = 100 kPa, G/s_u = 50, ν = 0.3) expanded from a₀ to 3a₀ on the
// same fixed mesh (the wall's triangles keep a third of their area), against
// the large-strain closed form (docs/continuum_pile.md §7). Measured −0.22 to
// −0.30 %; at half the rate (90 000 steps) within 0.02 % of that, so the
// loading is quasi-static. The outer radius b = 20 a₀ is felt: the pressure
// peaks near a/a₀ = 2.5, as the closed form's (c/b)³ term says.
TEST(SphericalCavity, TrescaPressureFollowsTheLargeStrainClosedFormToThreeTimesTheInitialRadius) {
  const double strength = 100e3;
  const constitutive::ElasticModuli moduli = constitutive::moduli_from_young_poisson(2.0 * 50.0 * strength * 1.3, 0.3);
  const auto model = std::make_shared<constitutive::MohrCoulombModel>(moduli, constitutive::MohrCoulombStrength{strength, 0.0, 0.0, 1e12});
  const CavityMeshSpec spec = test::spherical_test_mesh();
  const test::CavityRun run = test::expand_cavity(test::CavityShape::spherical, spec, model, kInSitu, {},
                                                  {45000, 0, {1.5, 2.0, 2.5, 3.0}});
  const TrescaCavity problem{CavityGeometry::spherical, moduli.shear, moduli.bulk, strength, kInSitu, spec.inner_radius, spec.outer_radius};
  for (std::size_t i = 0; i < run.pressures.size(); ++i) {
    const double exact = cavity_pressure(problem, run.radius_ratios[i] * spec.inner_radius);
    std::printf("sphere a/a0 = %.3f  p = %.1f kPa  closed form %.1f kPa  error %+.2f %%  unbalanced %.2e\n", run.radius_ratios[i],
                run.pressures[i] / 1e3, exact / 1e3, 100.0 * (run.pressures[i] - exact) / exact, run.unbalanced[i]);
    // 2 %: the tolerance for the limit pressure.
    EXPECT_NEAR(run.pressures[i], exact, 0.02 * exact) << "a/a0 = " << run.radius_ratios[i];
  }
  EXPECT_EQ(run.pressures.size(), 4u);
  std::printf("smallest area ratio %.3f, limit pressure (infinite medium) %.1f kPa\n", run.smallest_area_ratio, limit_pressure(problem) / 1e3);
}

// The same expansion with the mesh refined at a/a₀ = 2 (CGAL Delaunay
// refinement to 25°, docs/continuum_pile.md §4): the pressure stays on the
// closed form after the remesh.
TEST(SphericalCavity, TrescaPressureStaysOnTheClosedFormAfterARefiningRemesh) {
  const double strength = 100e3;
  const constitutive::ElasticModuli moduli = constitutive::moduli_from_young_poisson(2.0 * 50.0 * strength * 1.3, 0.3);
  const auto model = std::make_shared<constitutive::MohrCoulombModel>(moduli, constitutive::MohrCoulombStrength{strength, 0.0, 0.0, 1e12});
  const CavityMeshSpec spec = test::spherical_test_mesh();
  const TrescaCavity problem{CavityGeometry::spherical, moduli.shear, moduli.bulk, strength, kInSitu, spec.inner_radius, spec.outer_radius};
  test::CavityExpansion cavity(test::CavityShape::spherical, spec, model, kInSitu, {});
  cavity.expand_to(2.0, 15000);
  const double before = cavity.wall_pressure();
  const double angle_before = cavity.solver().smallest_angle_deg();
  const RemeshReport report = cavity.solver().remesh(25.0);
  const double angle_after = cavity.solver().smallest_angle_deg();
  cavity.expand_to(2.5, 7500);
  const double at_2_5 = cavity.wall_pressure();
  cavity.expand_to(3.0, 7500);
  const double at_3 = cavity.wall_pressure();
  const double exact_2 = cavity_pressure(problem, 2.0), exact_2_5 = cavity_pressure(problem, 2.5), exact_3 = cavity_pressure(problem, 3.0);
  std::printf("refined at a/a0 = 2: smallest angle %.1f -> %.1f deg, %zu -> %zu triangles, %zu nodes added, smallest area ratio at 3: %.3f\n"
              "  p(2) %+.2f %%, p(2.5) %+.2f %%, p(3) %+.2f %% from the closed form\n",
              angle_before, angle_after, report.triangles_before, report.triangles_after, report.nodes_added, cavity.solver().smallest_area_ratio(),
              100.0 * (before - exact_2) / exact_2, 100.0 * (at_2_5 - exact_2_5) / exact_2_5, 100.0 * (at_3 - exact_3) / exact_3);
  EXPECT_GT(report.nodes_added, 0u);  // the test means something only if the mesh was refined
  EXPECT_LT(angle_before, 25.0);
  EXPECT_GE(angle_after, 25.0 - 1e-9);
  // 2 %: the tolerance for the cavity pressure.
  EXPECT_NEAR(at_2_5, exact_2_5, 0.02 * exact_2_5);
  EXPECT_NEAR(at_3, exact_3, 0.02 * exact_3);
}

// Undrained Tresca (ν = 0.4999: total stress, the plastic flow and the
// elastic zone both at constant volume), the 20 × 8 mesh, expanded to
// a/a₀ = 1.5 in 30 000 steps and settled for 15 000: plain constant-strain
// triangles lock, either volumetric treatment follows the closed form.
TEST(SphericalCavity, UndrainedTrescaPressureLocksWithoutAVolumetricTreatmentAndNotWithIt) {
  const double strength = 100e3;
  const double poisson = 0.4999;
  const constitutive::ElasticModuli moduli = constitutive::moduli_from_young_poisson(2.0 * 50.0 * strength * (1.0 + poisson), poisson);
  const auto model = std::make_shared<constitutive::MohrCoulombModel>(moduli, constitutive::MohrCoulombStrength{strength, 0.0, 0.0, 1e12});
  const CavityMeshSpec spec = sphere_mesh(20);
  const TrescaCavity problem{CavityGeometry::spherical, moduli.shear, moduli.bulk, strength, kInSitu, spec.inner_radius, spec.outer_radius};
  const auto error = [&](VolumetricStrain treatment) {
    SolverSettings settings;
    settings.volumetric_strain = treatment;
    const test::CavityRun run = test::expand_cavity(test::CavityShape::spherical, spec, model, kInSitu, settings, {30000, 15000, {1.5}});
    const double exact = cavity_pressure(problem, run.radius_ratios.back() * spec.inner_radius);
    return (run.pressures.back() - exact) / exact;
  };
  const double plain = error(VolumetricStrain::element);
  const double averaged = error(VolumetricStrain::nodal_average);
  const double projected = error(VolumetricStrain::pressure_projection);
  std::printf("undrained Tresca sphere at a/a0 = 1.5, error from the closed form: %+.2f %% plain triangles, %+.2f %% nodal average, "
              "%+.2f %% pressure projection\n", 100.0 * plain, 100.0 * averaged, 100.0 * projected);
  // Measured +16.3 %, −0.56 % and −1.67 %. The projection is a little softer
  // than the average here: its stabilisation term is consistent only to
  // O(h |∇p| / G), and the plastic zone's pressure gradient 4 s_u/r is steep
  // (−1.13 % at half the loading rate; docs/continuum_pile.md §3). 2 %: the
  // issue's tolerance for the cavity pressure.
  EXPECT_GT(plain, 0.10);
  EXPECT_NEAR(averaged, 0.0, 0.02);
  EXPECT_NEAR(projected, 0.0, 0.02);
  EXPECT_LT(std::abs(projected), std::abs(plain));
}

}  // namespace
}  // namespace dfc::continuum
