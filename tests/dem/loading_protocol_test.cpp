// The loading-protocol registry (loading_protocol.hpp): each section enables
// its protocol and only it, at most one protocol replaces the step, and the
// protocols declare the units of the monitors they send.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "dem_test_support.hpp"
#include "dfc/dem/dem_backend.hpp"
#include "dfc/dem/dem_config.hpp"
#include "dfc/dem/loading_protocol.hpp"

namespace dfc::dem {
namespace {

nlohmann::json with_pile(nlohmann::json c) {
  c["pile"] = {{"radius_m", 0.008}, {"tip_z_m", 0.04}, {"length_m", 0.03}, {"velocity_m_s", {0, 0, -0.05}}};
  return c;
}

TEST(LoadingProtocols, EachSectionEnablesItsProtocolAndNoOther) {
  EXPECT_TRUE(make_loading_protocols(parse_dem_config(test::box_bed_config())).empty());
  const auto pile = make_loading_protocols(parse_dem_config(with_pile(test::box_bed_config())));
  ASSERT_EQ(pile.size(), 1u);
  EXPECT_FALSE(pile.front()->drives_step());   // the pile moves as a prescribed wall: the plain step
  EXPECT_FALSE(pile.front()->prepares_sample());
  const auto both = make_loading_protocols(parse_dem_config(with_pile(test::ucs_box_bed_config())));
  EXPECT_EQ(both.size(), 2u);
  std::set<std::string> sections;
  for (const LoadingProtocolEntry& entry : loading_protocol_registry()) {
    EXPECT_TRUE(sections.insert(std::string(entry.section)).second) << entry.section << " registered twice";
    EXPECT_EQ(entry.make(parse_dem_config(test::box_bed_config())), nullptr) << entry.section << " made without its section";
  }
}

// Every monitor a pile + UCS run sends has a declared unit (SPEC.md §6.3):
// the registry's declarations, not a list in the backend, cover the protocols'.
TEST(LoadingProtocols, TheirMonitorsAreDeclaredWithUnits) {
  DemBackend backend;
  const nlohmann::json info = backend.configure(with_pile(test::ucs_box_bed_config()));
  const nlohmann::json& units = info.at("monitor_units");
  const nlohmann::json monitors = backend.monitors();
  for (const char* name : {"pile_force_n", "pile_displacement_m", "axial_stress_pa", "axial_strain"}) {
    ASSERT_TRUE(monitors.contains(name)) << name;
    EXPECT_TRUE(units.contains(name)) << name;
  }
  for (const auto& [name, value] : monitors.items()) EXPECT_TRUE(units.contains(name)) << name << " has no declared unit";
  EXPECT_EQ(units.at("pile_force_n"), "N");
  EXPECT_EQ(units.at("axial_stress_pa"), "Pa");
}

}  // namespace
}  // namespace dfc::dem
