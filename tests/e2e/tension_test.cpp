// Direct tension of a bonded REV through the real coupler and DEM server: the
// periodic cell's triaxial loading with a negative axial strain rate pulls the
// cell along its axis while the servo holds the lateral edges at sigma_3 = 0
// (docs/dem_periodic.md), the experiment `./vc calibrate` reads a tensile
// strength from.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "command_runner.hpp"
#include "e2e_paths.hpp"
#include "results_series.hpp"

namespace dfc::testing {
namespace {

// The soft-bond REV of ucs_upscaling_small (S = 2, packing 11) pulled at 1/s
// to 0.25 % extension. Compression positive, so tension is a negative axial
// stress: it must reach a tensile peak well inside the run and fall to a
// fraction of it as the bonds fail, while the lateral stresses stay near
// zero (a uniaxial stress test, not a uniaxial strain one, whose lateral
// edges would carry a tension of their own). Measured: peak 240 kPa at
// 0.02 % extension, 3 kPa at the end.
TEST(DirectTension, ABondedRevPulledAlongItsAxisReachesATensilePeakAndBreaks) {
  const auto dir = fresh_directory("tension_rev_small");
  const CommandResult run = run_command({coupler(), "run", (e2e_dir() / "scenarios" / "tension_rev_small.json").string(), "--out", dir.string(),
                                         "--no-progress"},
                                        std::chrono::seconds(300));
  ASSERT_EQ(run.exit_status, 0) << run.output;
  const auto results = dir / "results.h5";
  const auto axial = series(results, "dem_axial_stress_pa");
  const auto strain = series(results, "dem_axial_strain");
  const auto peak = std::size_t(std::min_element(axial.begin(), axial.end()) - axial.begin());
  const double tensile_strength = -axial[peak];
  std::cout << "tensile strength " << tensile_strength << " Pa at axial strain " << strain[peak] << ", final " << axial.back() << " Pa\n";
  EXPECT_GT(tensile_strength, 50e3);                   // the bonds carry tension (their strength is 450 kPa)
  EXPECT_LT(strain.back(), 0.0);                       // extended: axial strain is compression positive
  EXPECT_LT(peak + 5, axial.size());                   // the peak well inside the run
  EXPECT_GT(axial.back(), -0.5 * tensile_strength);    // and softened after it
  EXPECT_GT(series(results, "dem_bonds_broken_shear").back() + series(results, "dem_bonds_broken_tension").back(),
            series(results, "dem_bonds_broken_shear").front() + series(results, "dem_bonds_broken_tension").front());
  for (const char* lateral : {"dem_cell_stress_xx_pa", "dem_cell_stress_yy_pa"}) {
    const auto s = series(results, lateral);
    EXPECT_LT(std::abs(s[peak]), 0.1 * tensile_strength) << lateral;
  }
}

}  // namespace
}  // namespace dfc::testing
