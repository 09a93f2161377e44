// Graded particle upscaling (docs/dem_generation.md §7) through the real
// coupler, DEM and FDM servers: a PCRM body with S = 5 within 4 mm of the
// axis and S = 10 beyond, equilibrated at 100 g. One run, every check on it
// (one process: the run takes most of the time).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "command_runner.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "e2e_paths.hpp"
#include "results_series.hpp"

namespace dfc::testing {
namespace {

/// Love–Weber stress of the particles whose centres lie in the ring
/// r_in <= r < r_out and depth band [d_top, d_bottom] below `surface`:
/// sum V_p sigma_p / V_ring (particle_stress.hpp), and its porosity.
struct Ring {
  double sigma_v = 0.0, sigma_h = 0.0, porosity = 0.0;
  std::size_t particles = 0;
};

Ring ring(const std::vector<double>& x, const std::vector<double>& radius, const std::vector<double>& stress, double r_in, double r_out,
          double surface, double d_top, double d_bottom) {
  Ring out;
  double solid = 0.0;
  for (std::size_t i = 0; i < radius.size(); ++i) {
    const double r = std::hypot(x[3 * i], x[3 * i + 1]), depth = surface - x[3 * i + 2];
    if (r < r_in || r >= r_out || depth < d_top || depth > d_bottom) continue;
    const double v = 4.0 / 3.0 * std::numbers::pi * std::pow(radius[i], 3);
    solid += v;
    out.sigma_v += v * stress[6 * i + 5];
    out.sigma_h += v * 0.5 * (stress[6 * i] + stress[6 * i + 3]);
    ++out.particles;
  }
  const double volume = std::numbers::pi * (r_out * r_out - r_in * r_in) * (d_bottom - d_top);
  out.sigma_v /= volume;
  out.sigma_h /= volume;
  out.porosity = 1.0 - solid / volume;
  return out;
}

TEST(GradedGeneration, TwoZonesFilledFromOneRevCarryTheSelfWeightField) {
  const auto dir = fresh_directory("centrifuge_generation_graded_small");
  const CommandResult result = run_command(
      {coupler(), "run", (e2e_dir() / "scenarios" / "centrifuge_generation_graded_small.json").string(), "--out", dir.string(), "--no-progress"},
      std::chrono::seconds(400));
  ASSERT_EQ(result.exit_status, 0) << result.output;
  const auto results = dir / "results.h5";
  const h5::File file = h5::File::open_read_only(results);
  const auto generation = nlohmann::json::parse(h5::read_string_attribute(file, "/", "versions"))["dem"]["configured"]["generation"];
  const auto summary = nlohmann::json::parse(h5::read_string_attribute(file, "/", "summary"));
  ASSERT_TRUE(summary.value("equilibrium_reached", false)) << summary.dump();

  // The zones as configured: S = 5, then 10, each with spheres.
  ASSERT_EQ(generation["zones"].size(), 2u);
  EXPECT_EQ(generation["zones"][0]["scale_factor"].get<double>(), 5.0);
  EXPECT_EQ(generation["zones"][1]["scale_factor"].get<double>(), 10.0);
  const std::string dem = last_snapshot(file, "dem");
  const auto x = h5::read_f64(file, dem + "/particle_position");
  const auto radius = h5::read_f64(file, dem + "/particle_radius");
  const auto stress = h5::read_f64(file, dem + "/particle_stress_pa");
  const auto material = h5::read_i64(file, dem + "/particle_material");
  ASSERT_EQ(material.size(), radius.size());
  // Every sphere in its zone: the fine zone's centres lie within 4 mm of the
  // axis (plus their radius, up to 0.45 mm at S = 5: a fine sphere seated on
  // the coarse packing moves by at most that), the coarse zone's beyond
  // (0.1 mm: the equilibration's motion).
  for (std::size_t i = 0; i < radius.size(); ++i) {
    const double r = std::hypot(x[3 * i], x[3 * i + 1]);
    if (material[i] == 0) EXPECT_LE(r, 4e-3 + radius[i] + 1e-4) << "sphere " << i;
    else EXPECT_GT(r, 4e-3 - 1e-4) << "sphere " << i;
    EXPECT_LE(radius[i], material[i] == 0 ? 0.46e-3 : 0.91e-3);
  }

  // Depth band: the interior, one coarse REV cell (8 mm) from the top and the floor.
  const double surface = generation["surface_z_m"].get<double>(), gamma = generation["unit_weight_n_m3"].get<double>(), k0 = generation["k0"].get<double>();
  const double d_top = 8e-3, d_bottom = 24e-3, theory = gamma * 0.5 * (d_top + d_bottom);
  // Rings away from the seam at 4 mm (rings by centres astride it mix the
  // two zones' spheres by where their centres fall, so they do not measure
  // the seam). Measured on this variant with the seam balance
  // (seam_balance.hpp): sigma_v 0.98 of gamma z in the fine core and 0.95 in
  // the coarse ring (this small core hangs weight on the coupling wall by
  // friction: -4 % in the uniform small variant), sigma_h 1.01 of K0 gamma z
  // in both; without the balance the seam bonds formed unloaded and the fine
  // core kept 0.78 of its sigma_h. Asserted: the "no jump above 5 %"
  // across the seam for both components, sigma_h within 5 % of K0 gamma z
  // in both zones, sigma_v within 10 % (the friction on the coupling wall).
  const Ring fine = ring(x, radius, stress, 0.0, 3e-3, surface, d_top, d_bottom);
  const Ring coarse = ring(x, radius, stress, 5e-3, 8.2e-3, surface, d_top, d_bottom);
  for (const auto& [name, g] : {std::pair{"fine, r < 3 mm", fine}, {"coarse, 5-8.2 mm", coarse}})
    std::cout << name << ": " << g.particles << " spheres, sigma_v / gamma z " << g.sigma_v / theory << ", sigma_h / K0 gamma z "
              << g.sigma_h / (k0 * theory) << ", porosity " << g.porosity << "\n";
  EXPECT_NEAR(coarse.sigma_v, theory, 0.10 * theory);
  EXPECT_NEAR(fine.sigma_v, theory, 0.10 * theory);
  EXPECT_NEAR(fine.sigma_v / coarse.sigma_v, 1.0, 0.05);
  EXPECT_NEAR(coarse.sigma_h, k0 * theory, 0.05 * k0 * theory);
  EXPECT_NEAR(fine.sigma_h, k0 * theory, 0.05 * k0 * theory);
  EXPECT_NEAR(fine.sigma_h / coarse.sigma_h, 1.0, 0.05);
  // Porosity of each zone away from the seam and the walls, over 4-28 mm
  // deep: the REV's. A ring samples the REV's copies, all identical, over a
  // section that is no whole number of periods (the coarse ring is two REV
  // cells of area), so its noise is one REV's, not averaged over the copies:
  // over eight REVs (seeds 5-8, both dem.timestep.stiffness_bound choices)
  // the fine core lay within -0.002/+0.014 and the coarse ring within
  // -0.010/+0.020 of the REV. Asserted: +-0.025 (the issue's +-0.01 does not
  // tell one REV realization from another at this size); a zone filled from
  // the wrong cell or with gaps at the copies' faces is off by more.
  const double rev = generation["rev_porosity"].get<double>();
  EXPECT_NEAR(ring(x, radius, stress, 0.0, 3e-3, surface, 4e-3, 28e-3).porosity, rev, 0.025);
  EXPECT_NEAR(ring(x, radius, stress, 5e-3, 8.2e-3, surface, 4e-3, 28e-3).porosity, rev, 0.025);

  // The profile slices are one REV cell of the coarsest zone high (0.8 mm x
  // S = 10 = 8 mm: four over the 32 mm body), not one cell of the REV as
  // prepared at S = 5: a slice spans both zones, and thinner ones average
  // too few coarse layers (docs/dem_generation.md §4).
  const auto depth = h5::read_f64(file, dem + "/profile_depth_m");
  ASSERT_EQ(depth.size(), 4u);
  EXPECT_NEAR(depth[1] - depth[0], 8e-3, 1e-9);

  // The generation and equilibration break no bond, the seam's new ones included.
  EXPECT_EQ(series(results, "dem_bonds_broken_tension").back(), 0.0);
  EXPECT_EQ(series(results, "dem_bonds_broken_shear").back(), 0.0);
}

}  // namespace
}  // namespace dfc::testing
