// The coupler's estimate of a DEM snapshot, array by array
// (coupler/include/dfc/coupler/snapshot_estimate.hpp): a model whose bond or
// contact arrays would pass the protocol's limit per array is refused at
// configure time with the key to change. The estimate before it counted the
// positions only (24 B per particle), which let these models start.
#include <gtest/gtest.h>

#include <string>

#include "dfc/common/errors.hpp"
#include "dfc/coupler/snapshot_estimate.hpp"

namespace dfc::coupler {
namespace {

const double kLimit = 256.0 * (1 << 20);  // the protocol's 256 MiB per array (SPEC.md §8)

/// The ConfigError the estimate throws for a DEM section and its monitors, or "" if none.
ConfigError refusal(const nlohmann::json& config, const nlohmann::json& monitors, std::optional<double> memory = std::nullopt) {
  try {
    check_snapshot_estimate(estimate_dem_snapshot(config, monitors, "participants.dem"), kLimit, memory);
  } catch (const ConfigError& e) {
    return e;
  }
  return ConfigError("", "");
}

/// The bonded pile of docs/looking_at_a_run.md §4 scaled up: 3.4 bonds per particle.
nlohmann::json bonded(double particles) {
  return {{"particle_count", particles}, {"contact_count", 0.0}, {"bonds_intact", 3.4 * particles}, {"bonds_damaged", 0.0},
          {"bonds_broken_tension", 0.0}, {"bonds_broken_shear", 0.0}};
}

TEST(SnapshotEstimate, BondArraysOverTheLimitNameSnapshotContents) {
  const double particles = 3.4e6;
  // The positions alone, all the old check looked at, fit.
  ASSERT_LT(particles * 24.0, kLimit);
  const ConfigError e = refusal({{"particles", {{"count", particles}}}}, bonded(particles));
  EXPECT_EQ(e.key_path(), "participants.dem.config.snapshot.contents");
  EXPECT_NE(e.reason().find("bond_position"), std::string::npos) << e.reason();
  EXPECT_NE(e.reason().find("\"bonds\""), std::string::npos) << e.reason();
}

TEST(SnapshotEstimate, BondsLeftOutOfTheContentsFit) {
  const double particles = 3.4e6;
  const nlohmann::json config = {{"snapshot", {{"contents", {"particle_stress", "walls"}}}}};
  EXPECT_EQ(refusal(config, bonded(particles)).key_path(), "");
  // Each array of the estimate is one the server writes with these contents.
  for (const auto& a : estimate_dem_snapshot(config, bonded(particles), "participants.dem")) EXPECT_FALSE(a.name.starts_with("bond_")) << a.name;
}

TEST(SnapshotEstimate, ContactsCountAtLeastADensePackingAndNameTheMinimumForce) {
  // An unbonded bed before its first step reports no contacts; loaded, it has
  // about 3 per particle, and contact_force_n (24 B each) passes the limit.
  const double particles = 3.9e6;
  const nlohmann::json monitors = {{"particle_count", particles}, {"contact_count", 0.0}};
  const nlohmann::json contacts = {{"snapshot", {{"contents", {"contacts"}}}}};
  const ConfigError e = refusal(contacts, monitors);
  EXPECT_EQ(e.key_path(), "participants.dem.config.snapshot.contacts_min_force_n");
  EXPECT_NE(e.reason().find("contact_force_n"), std::string::npos) << e.reason();
  // Without contacts (the default contents) the same bed fits.
  EXPECT_EQ(refusal(nlohmann::json::object(), monitors).key_path(), "");
}

TEST(SnapshotEstimate, ParticleStressIsTheLargestParticleArray) {
  // 48 B per particle: over the limit from 5.6 million particles, while the positions (24 B) are not.
  const nlohmann::json monitors = {{"particle_count", 6e6}};
  EXPECT_EQ(refusal(nlohmann::json::object(), monitors).key_path(), "participants.dem.config.snapshot.contents");
  EXPECT_EQ(refusal({{"snapshot", {{"contents", nlohmann::json::array()}}}}, monitors).key_path(), "");
  // Positions over the limit name the particles.
  EXPECT_EQ(refusal({{"particles", {{"count", 1.2e7}}}, {"snapshot", {{"contents", nlohmann::json::array()}}}}, {{"particle_count", 1.2e7}}).key_path(),
            "participants.dem.config.particles");
}

TEST(SnapshotEstimate, MemoryCountsEveryArray) {
  // 1e6 particles, 3.4e6 bonds, default contents: 112 B per particle and
  // 88 B per bond, about 0.41 GiB a snapshot, about three times that to take it.
  const auto arrays = estimate_dem_snapshot(nlohmann::json::object(), bonded(1e6), "participants.dem");
  double bytes = 0.0;
  for (const auto& a : arrays) bytes += a.bytes();
  EXPECT_DOUBLE_EQ(bytes, 1e6 * 112.0 + 3.4e6 * 88.0);
  EXPECT_EQ(refusal(nlohmann::json::object(), bonded(1e6), 3.0 * bytes * 1.01).key_path(), "");
  const ConfigError e = refusal(nlohmann::json::object(), bonded(1e6), 3.0 * bytes * 0.99);
  EXPECT_EQ(e.key_path(), "participants.dem.config");
  EXPECT_NE(e.reason().find("snapshot.contents"), std::string::npos) << e.reason();
}

TEST(SnapshotEstimate, NoParticleCountNoEstimate) {
  EXPECT_TRUE(estimate_dem_snapshot(nlohmann::json::object(), {{"zone_count", 1e9}}, "participants.continuum").empty());
}

}  // namespace
}  // namespace dfc::coupler
