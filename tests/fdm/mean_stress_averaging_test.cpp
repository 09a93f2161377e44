// The stress pass of mixed discretization (docs/theory/fdm.md §1.5, last
// paragraph), offered to models with plastic volume change.
#include <gtest/gtest.h>

#include <array>

#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/fdm/mixed_discretization.hpp"
#include "dfc/constitutive/mohr_coulomb_model.hpp"
#include "dfc/constitutive/structured_cam_clay_model.hpp"

namespace dfc::fdm {
namespace {

TEST(MeanStressAveraging, ReplacesEachMeanIncrementByTheVolumeAverageAndKeepsDeviators) {
  std::array<SymTensor, 3> stress = {SymTensor{-1.0, -2.0, -3.0, 0.5, 0.0, 0.0}, SymTensor{-4.0, -4.0, -4.0, 0.0, 0.0, 0.0},
                                     SymTensor{1.0, 1.0, 1.0, 0.0, 0.2, 0.0}};
  const std::array<double, 3> old_means = {-1.0, -1.0, 0.0};  // increments −1, −3, +1
  const std::array<double, 3> volumes = {1.0, 2.0, 1.0};      // average (−1 − 6 + 1)/4 = −1.5
  const std::array<SymTensor, 3> before = stress;
  apply_mean_stress_mixed_discretization(stress, old_means, volumes);
  for (std::size_t t = 0; t < 3; ++t) {
    EXPECT_NEAR(stress[t].trace() / 3.0 - old_means[t], -1.5, 1e-15);
    const SymTensor d = stress[t].deviator() - before[t].deviator();
    EXPECT_NEAR(d.norm(), 0.0, 1e-15);
  }
}

TEST(MeanStressAveraging, OnlyPlasticModelsWithVolumeChangeAskForIt) {
  EXPECT_FALSE(constitutive::ElasticModel(constitutive::ElasticModuli{1e6, 1e6}).needs_mean_stress_averaging());  // keeps the elastic path fast
  constitutive::StructuredCamClayParameters m;
  m.moduli = constitutive::ElasticModuli{1e6, 1e6};
  m.ps0 = 1e5;
  EXPECT_TRUE(constitutive::StructuredCamClayModel(m).needs_mean_stress_averaging());
}

}  // namespace
}  // namespace dfc::fdm
