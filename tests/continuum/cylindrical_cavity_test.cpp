// Cylindrical cavity expansion from a₀ to 3a₀ in an elastic–perfectly plastic
// Tresca material (docs/continuum_pile.md §7), against the large-strain closed
// form of the same constitutive assumptions (Gibson & Anderson 1961 with the
// elastic compressibility, Yu & Houlsby 1991 limit).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/constitutive/mohr_coulomb_model.hpp"
#include "cavity_expansion.hpp"
#include "dfc/continuum/tresca_cavity_closed_form.hpp"

namespace dfc::continuum {
namespace {

// s_u = 100 kPa, G/s_u = 50, ν = 0.49 (nearly incompressible: the elements
// must not lock), σ₀ = 200 kPa, a₀ = 1 m, b = 100 a₀.
constexpr double kStrength = 100e3;
constexpr double kInSitu = 200e3;
constexpr double kInitialRadius = 1.0;
constexpr double kOuterRadius = 100.0;
const constitutive::ElasticModuli kModuli = constitutive::moduli_from_young_poisson(2.0 * 50.0 * kStrength * 1.49, 0.49);

// 60 radial divisions graded by 1.075 from a₀ to b = 100 a₀ (the first ring
// 0.1 a₀ wide, 0.033 a₀ at a = 3a₀), one layer 0.1 a₀ high: 120 triangles. The
// cavity wall's elements stay well shaped up to a/a₀ = 3 (aspect ratio 3 at
// the end), so no remeshing is needed for this test.
// (test::cylindrical_test_mesh(): a₀ = kInitialRadius, b = kOuterRadius.)
CavityMeshSpec strip() { return test::cylindrical_test_mesh(); }

test::CavityRun expand(std::shared_ptr<const constitutive::ConstitutiveModel> model, const SolverSettings& settings,
                       const test::Loading& loading) {
  return test::expand_cavity(test::CavityShape::cylindrical, strip(), std::move(model), kInSitu, settings, loading);
}

TrescaCavity closed_form_problem() {
  return {CavityGeometry::cylindrical, kModuli.shear, kModuli.bulk, kStrength, kInSitu, kInitialRadius, kOuterRadius};
}

TEST(CylindricalCavity, TrescaPressureFollowsTheLargeStrainClosedFormToThreeTimesTheInitialRadius) {
  // Tresca = Mohr–Coulomb with φ = ψ = 0, cohesion s_u; no tension cut-off in reach.
  const constitutive::MohrCoulombStrength tresca{kStrength, 0.0, 0.0, 1e12};
  // 300 000 steps (the wall moves 6.7e-6 a₀ per step): halving the rate
  // halves the error (+0.60 % → +0.29 % at a/a₀ = 3), so what remains is the
  // inertia of the pseudo-dynamic loading, first order in its rate.
  const test::CavityRun run =
      expand(std::make_shared<constitutive::MohrCoulombModel>(kModuli, tresca), {}, {300000, 0, {1.5, 2.0, 2.5, 3.0}});
  const TrescaCavity problem = closed_form_problem();
  ASSERT_EQ(run.pressures.size(), 4u);
  for (std::size_t i = 0; i < run.pressures.size(); ++i) {
    const double exact = cavity_pressure(problem, run.radius_ratios[i] * kInitialRadius);
    std::printf("a/a0 = %.3f  p = %.1f kPa  closed form %.1f kPa  error %+.2f %%  unbalanced %.2e\n", run.radius_ratios[i],
                run.pressures[i] / 1e3, exact / 1e3, 100.0 * (run.pressures[i] - exact) / exact, run.unbalanced[i]);
    // 2 %: the tolerance for the limit pressure.
    EXPECT_NEAR(run.pressures[i], exact, 0.02 * exact) << "a/a0 = " << run.radius_ratios[i];
    // Quasi-static: the unbalanced force stays below 1 % of the forces it balances.
    EXPECT_LT(run.unbalanced[i], 0.01) << "a/a0 = " << run.radius_ratios[i];
  }
  std::printf("smallest area ratio %.3f, limit pressure (infinite medium) %.1f kPa\n", run.smallest_area_ratio,
              limit_pressure(problem) / 1e3);
}

// Elastic, ν = 0.4999 (K/G = 5000), a/a₀ = 1.001: Lamé's cavity in plane
// strain with the pressure σ₀ held at b, p − σ₀ = 2G (u/a)(1 − a²/b²) for an
// incompressible medium (Timoshenko & Goodier 1970); ν = 0.4999 differs by
// O((1 − 2ν) a²/b²) = 2e-8.
TEST(CylindricalCavity, NearlyIncompressibleElasticWallPressureIsLames) {
  const double poisson = 0.4999;
  const constitutive::ElasticModuli moduli = constitutive::moduli_from_young_poisson(2.0 * 1e7 * (1.0 + poisson), poisson);
  const auto model = std::make_shared<constitutive::ElasticModel>(moduli);
  const test::Loading loading{20000, 100000, {1.001}};
  const double strain = 1e-3;
  const double lame = kInSitu + 2.0 * moduli.shear * strain * (1.0 - 1.0 / (kOuterRadius * kOuterRadius));
  const test::CavityRun run = expand(model, {}, loading);
  const double error = (run.pressures.back() - lame) / (lame - kInSitu);
  std::printf("elastic nu = 0.4999: wall pressure change error %+.3f %% (unbalanced %.1e)\n", 100.0 * error, run.unbalanced.back());
  // Measured −0.081 % (+0.015 % with 30 radial divisions): both below the
  // O(u/a) = 0.1 % by which the small-strain closed form differs from the
  // solver's logarithmic strain, so refinement cannot show here. 0.5 % of
  // the pressure change. (This radial field is isochoric node by node, so it
  // cannot show locking; the spherical cavity on a meridian mesh does,
  // tests/continuum/spherical_cavity_test.cpp.)
  EXPECT_NEAR(error, 0.0, 0.005);
}

}  // namespace
}  // namespace dfc::continuum
