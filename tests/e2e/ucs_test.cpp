// Uniaxial compression of a bonded soft-rock sample through the real coupler
// and DEM server (docs/dem_ucs.md): the stress–strain curve read back from the
// results file must show a peak followed by softening, bonds must break, and
// the peak must be the calibrated UCS.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include "command_runner.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "e2e_paths.hpp"
#include "results_series.hpp"

namespace dfc::testing {
namespace {

// A brittle bonded sample under displacement control: the axial stress rises
// to a peak (UCS) where shear bond failures localise, then drops as the
// sample splits. With the small scenario the stress falls to a few percent of
// the peak (measured 394 kPa -> 8 kPa); asking for peak > 1.2 x final is the
// issue's criterion and stays far from that margin. Strain at the peak must be
// positive: the platens are seated on the sample, so loading starts at once and
// the peak lies after the start. Broken bonds must increase, as the softening
// comes from bond breakage and not from a numerical artefact.
//
// The calibrated value: the small sample's UCS with the soft-bond parameters
// of Zheng et al. (2023) Table 2 and the bond gap chosen here (docs/dem_ucs.md).
// The run is bit-for-bit deterministic (one thread), but its peak is chaotic
// under round-off: the same scenario with the strain rate changed by ±1e-12,
// ±1e-11 and ±1e-9 of itself (changes that alter only the last bits of the
// platen motion) peaked at 383.3 / 386.2 / 388.0 / 388.9 / 393.2 / 400.4 /
// 403.2 kPa, -2.8 % to +2.2 % about the unchanged 394.4 kPa (sd 1.7 %). A
// compiler or library that rounds differently lands in that band; ±6 %
// (about twice the largest of those deviations) keeps it clear, while a change
// of the calibration itself falls outside: a bond gap of 0.04 mm instead of
// 0.06 gives 107 kPa, and the UCS moves about in proportion to the bond
// strengths (±10 % strength, ±10 % UCS).
TEST(Ucs, SoftBondSampleShowsPeakSofteningBondBreakageAndItsCalibratedStrength) {
  const auto dir = fresh_directory("ucs_softbond_small");
  const std::vector<std::string> argv{coupler(), "run", (e2e_dir() / "scenarios" / "ucs_softbond_small.json").string(), "--out", dir.string(),
                                      "--no-progress"};
  const CommandResult result = run_command(argv, std::chrono::seconds(300));
  ASSERT_EQ(result.exit_status, 0) << result.output;
  const auto results = dir / "results.h5";
  const auto stress = series(results, "dem_axial_stress_pa");
  const auto strain = series(results, "dem_axial_strain");
  const auto tension = series(results, "dem_bonds_broken_tension");
  const auto shear = series(results, "dem_bonds_broken_shear");
  ASSERT_GT(stress.size(), 10u);
  ASSERT_EQ(stress.size(), strain.size());

  const auto peak = std::max_element(stress.begin(), stress.end());
  const auto at_peak = static_cast<std::size_t>(peak - stress.begin());
  std::cout << "UCS small: peak " << *peak << " Pa at axial strain " << strain[at_peak] << ", final " << stress.back() << " Pa at "
            << strain.back() << "; broken bonds tension " << tension.back() << ", shear " << shear.back() << "\n";
  EXPECT_GT(*peak, 0.0);
  EXPECT_GT(strain[at_peak], 0.0);
  EXPECT_LT(at_peak + 1, stress.size()) << "the peak is the last sample: no softening branch";
  EXPECT_GT(*peak, 1.2 * stress.back());
  // Compression shortens the sample monotonically (the platens are driven).
  for (std::size_t i = 1; i < strain.size(); ++i) ASSERT_GE(strain[i], strain[i - 1]) << "sample " << i;
  EXPECT_GT(tension.back() + shear.back(), tension.front() + shear.front());
  constexpr double calibrated = 394.4e3;  // Pa, measured 2026-12-01
  EXPECT_NEAR(*peak, calibrated, 0.06 * calibrated);
}

}  // namespace
}  // namespace dfc::testing
