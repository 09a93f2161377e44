// The spherical cavity on a meridian mesh (docs/continuum_pile.md §3): a
// two-dimensional triangulation of a one-dimensional field, where
// constant-strain triangles lock when the material is nearly incompressible
// and the nodal-averaged volumetric strain must not.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "cavity_expansion.hpp"
#include "dfc/constitutive/elastic_model.hpp"

namespace dfc::continuum {
namespace {

constexpr double kInSitu = 200e3;

// Elastic, ν = 0.499, a/a₀ = 1.001: Lamé's spherical cavity with the pressure
// σ₀ held at b, p − σ₀ = 4G (u/a)(1 − a³/b³) for an incompressible medium
// (Timoshenko & Goodier 1970); ν = 0.499 differs by O((1 − 2ν) a³/b³) = 3e-7.
TEST(SphericalCavity, NearlyIncompressibleElasticWallPressureIsLamesOnlyWithTheNodalAverage) {
  const double poisson = 0.499;
  const constitutive::ElasticModuli moduli = constitutive::moduli_from_young_poisson(2.0 * 1e7 * (1.0 + poisson), poisson);
  const auto model = std::make_shared<constitutive::ElasticModel>(moduli);
  const test::Loading loading{20000, 30000, {1.001}};
  const double strain = 1e-3;
  const CavityMeshSpec spec = test::spherical_test_mesh();
  const double ratio = spec.inner_radius / spec.outer_radius;
  const double lame = 4.0 * moduli.shear * strain * (1.0 - ratio * ratio * ratio);

  const test::CavityRun averaged =
      test::expand_cavity(test::CavityShape::spherical, spec, model, kInSitu, {}, loading);
  SolverSettings plain;
  plain.average_volumetric_strain = false;
  const test::CavityRun locked =
      test::expand_cavity(test::CavityShape::spherical, spec, model, kInSitu, plain, loading);
  const double averaged_error = (averaged.pressures.back() - kInSitu - lame) / lame;
  const double locked_error = (locked.pressures.back() - kInSitu - lame) / lame;
  std::printf("spherical, nu = 0.499: wall pressure change error %+.2f %% with the nodal average (unbalanced %.1e), %+.1f %% without\n",
              100.0 * averaged_error, averaged.unbalanced.back(), 100.0 * locked_error);
  // Measured −0.20 % with the average, +2.7 % without. 1 %: the
  // discretisation of a 1/ρ³ field by constant-strain rings 0.12 a₀ wide at
  // the wall (−0.37 % on a 40 × 16 mesh, +4.4 % on 20 × 8), plus O(u/a) = 0.1 %
  // of large strain against the small-strain closed form.
  EXPECT_NEAR(averaged_error, 0.0, 0.01);
  // Without the average the same mesh locks: too stiff by more than 2 %. (At
  // ν = 0.4999 the average leaves +10 % against +35 % without: it reduces the
  // locking but does not remove it; docs/continuum_pile.md §3.)
  EXPECT_GT(locked_error, 0.02);
}

}  // namespace
}  // namespace dfc::continuum
