// Particle upscaling of bonded rock through the real coupler and DEM server
// (docs/dem_upscaling.md; issue 3; Zheng et al. 2023 Fig. 4; Zheng & Ciantia 2025 user guide Eq. 5,
// docs/theory/dem_contact_laws.md §3.7). Both scenarios run their variants from one file
// ("variants", coupler/include/dfc/coupler/scenario_variants.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>

#include "command_runner.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "e2e_paths.hpp"
#include "results_series.hpp"

namespace dfc::testing {
namespace {

/// Runs every variant of an e2e scenario into a fresh folder; returns the folder.
std::filesystem::path run_variants(const std::string& scenario) {
  const auto dir = fresh_directory(scenario);
  const std::vector<std::string> argv{coupler(), "run", (e2e_dir() / "scenarios" / (scenario + ".json")).string(), "--out", dir.string(), "--no-progress"};
  const CommandResult result = run_command(argv, std::chrono::seconds(300));
  EXPECT_EQ(result.exit_status, 0) << result.output;
  return dir;
}

struct Curve {
  double peak = 0.0;       ///< Pa
  std::size_t at_peak = 0;
  double stiffness = 0.0;  ///< Pa, least-squares slope of the pre-peak points below 30 % of the peak
  double final = 0.0;      ///< Pa
};

/// The same measures tools/plot_results.py prints for an overlay.
Curve measure_curve(const std::vector<double>& strain, const std::vector<double>& stress) {
  Curve c;
  c.at_peak = std::size_t(std::max_element(stress.begin(), stress.end()) - stress.begin());
  c.peak = stress[c.at_peak];
  c.final = stress.back();
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (std::size_t i = 0; i <= c.at_peak; ++i) {
    if (stress[i] > 0.3 * c.peak) continue;
    sx += strain[i], sy += stress[i], sxx += strain[i] * strain[i], sxy += strain[i] * stress[i], n += 1;
  }
  c.stiffness = n >= 2 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : std::nan("");
  return c;
}

double spread(const std::vector<double>& v) {
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return (*hi - *lo) / (std::accumulate(v.begin(), v.end(), 0.0) / double(v.size()));
}

// The soft-bond rock of ucs_softbond as a periodic REV, unconfined, at S = 1
// and 2 in the same 12 mm cell (about 2300 and 290 spheres). The issue's
// criteria are peaks within ±10 % of each other and initial stiffness within
// ±15 %; a spread (max − min)/mean below 10 % and 15 % is the stricter reading
// (±10 % about the mean allows 20 %).
//
// One 290-sphere packing is too small to stand for S = 2: round-off alone
// moved its peak by 10 % (a rotation formula that changed only the last bits
// gave 714.6 -> 787.8 kPa; docs/dem_upscaling.md), and five seeds spread over
// 616-705 kPa. So S = 2 runs in five packings (seeds 11-15) and enters the
// comparison by its mean (measured: S = 1 708.8 kPa against a mean of
// 661.9 kPa, spread 6.8 %; stiffness 7.8 %); the mean of five has about 1/sqrt(5) of a single
// packing's scatter, which leaves the 10 % criterion a real margin. Each
// curve must also be a peak followed by softening (the peak is not the last
// sample and the final stress is below 80 % of it), or the comparison would
// be of unfinished loading.
TEST(UpscalingRules, SoftBondRevKeepsPeakAndStiffnessAcrossScaleFactors) {
  const auto dir = run_variants("ucs_upscaling_small");
  const auto curve = [&](const std::string& label) {
    const auto results = dir / label / "results.h5";
    const Curve c = measure_curve(series(results, "dem_axial_strain"), series(results, "dem_axial_stress_pa"));
    std::cout << label << ": peak " << c.peak << " Pa, initial stiffness " << c.stiffness << " Pa, final " << c.final << " Pa\n";
    EXPECT_LT(c.at_peak + 1, series(results, "dem_axial_stress_pa").size()) << label << ": no softening branch";
    EXPECT_LT(c.final, 0.8 * c.peak) << label;
    EXPECT_GT(series(results, "dem_bonds_broken_shear").back(), 0.0) << label;
    return c;
  };
  const Curve s1 = curve("S1");
  double peak2 = 0.0, stiffness2 = 0.0;
  const std::vector<std::string> seeds{"S2_seed11", "S2_seed12", "S2_seed13", "S2_seed14", "S2_seed15"};
  for (const auto& label : seeds) {
    const Curve c = curve(label);
    peak2 += c.peak / double(seeds.size());
    stiffness2 += c.stiffness / double(seeds.size());
  }
  std::cout << "S2, mean of " << seeds.size() << " packings: peak " << peak2 << " Pa, initial stiffness " << stiffness2 << " Pa\n";
  EXPECT_LT(spread({s1.peak, peak2}), 0.10);
  EXPECT_LT(spread({s1.stiffness, stiffness2}), 0.15);
}

// Exact similarity: with the cell edge and the strain rate scaled with S as
// well, a model whose every parameter follows its declared rule (radii, u_c
// and the bond gap x S; moduli, strengths, theta_c, damping and step fraction
// fixed) has the same dimensionless response at any S. With S a power of two
// every scaled number is exact in binary floating point, so the response must
// agree bit for bit: a parameter left unscaled, or any absolute length, time
// or force hidden in the DEM, would show here (S = 10 or 100 instead diverge
// by round-off, which the chaotic granular dynamics amplify: the full
// scenario compares those at REV size). The damage-bond sample must also show
// a peak of the deviatoric stress with damaged and broken bonds.
TEST(UpscalingRules, DamageBondResponseIsExactlyScaleInvariant) {
  const auto dir = run_variants("triaxial_damagebond_small");
  const auto base = dir / "S1" / "results.h5";
  const auto q = series(base, "dem_deviatoric_stress_pa");
  const Curve c = measure_curve(series(base, "dem_axial_strain"), q);
  std::cout << "S1: peak deviator " << c.peak << " Pa at sample " << c.at_peak << " of " << q.size() << ", final " << c.final << " Pa\n";
  EXPECT_GT(c.peak, 1e6);  // strongly bonded chalk at 100 kPa: MPa deviator (measured 3.4 MPa)
  EXPECT_LT(c.final, 0.8 * c.peak);
  EXPECT_GT(series(base, "dem_bonds_damaged")[c.at_peak], 0.0);
  EXPECT_GT(series(base, "dem_bonds_broken_shear").back() + series(base, "dem_bonds_broken_tension").back(), 0.0);
  for (const char* label : {"S2", "S4"}) {
    const auto other = dir / label / "results.h5";
    for (const std::string column : {"dem_deviatoric_stress_pa", "dem_axial_strain", "dem_cell_stress_xx_pa", "dem_porosity", "dem_bonds_intact",
                                     "dem_bonds_broken_shear", "dem_coordination_number"})
      EXPECT_EQ(series(other, column), series(base, column)) << label << " " << column;
  }
}

}  // namespace
}  // namespace dfc::testing
