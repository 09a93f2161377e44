// Scenario reading (README, "Scenarios"): defaults, gravity injection, program lookup,
// and errors that name the key path.
#include <gtest/gtest.h>

#include <cmath>

#include "dfc/common/errors.hpp"
#include "dfc/coupler/scenario.hpp"

namespace dfc::coupler {
namespace {

nlohmann::json minimal() {
  return {{"schema_version", 1},
          {"name", "t"},
          {"participants", {{"continuum", {{"program", "/bin/true"}, {"config", nlohmann::json::object()}}}}},
          {"run", {{"exchanges", 3}}}};
}

std::string error_key(const nlohmann::json& document) {
  try {
    (void)parse_scenario(document, "scenario.json", "");
  } catch (const ConfigError& e) {
    return e.key_path();
  }
  return "(no error)";
}

TEST(Scenario, DefaultsAndGravityInjection) {
  auto document = minimal();
  document["gravity"] = {{"g_m_s2", 9.81}, {"g_level", 50}};
  const Scenario s = parse_scenario(document, "scenario.json", "");
  ASSERT_EQ(s.participants.size(), 1u);
  EXPECT_EQ(s.participants[0].slot, "continuum");
  EXPECT_EQ(s.run.exchanges, 3);
  EXPECT_EQ(s.coupling.exchange_interval, 1);
  EXPECT_EQ(s.output_directory, std::filesystem::path("results/t"));
  // N·g along -z, injected into the section the server receives.
  const auto g = s.participants[0].config.at("gravity_m_s2").get<std::vector<double>>();
  EXPECT_DOUBLE_EQ(g[2], -9.81 * 50);
  EXPECT_DOUBLE_EQ(g[0], 0.0);
}

TEST(Scenario, GravityDirectionIsNormalised) {
  auto document = minimal();
  document["gravity"] = {{"g_m_s2", 10.0}, {"direction", {0, 3, -4}}};
  const Scenario s = parse_scenario(document, "scenario.json", "");
  EXPECT_NEAR(s.gravity_m_s2[1], 6.0, 1e-12);
  EXPECT_NEAR(s.gravity_m_s2[2], -8.0, 1e-12);
}

TEST(Scenario, ErrorsNameTheKeyPath) {
  auto d = minimal();
  d["run"]["exchanges"] = -1;
  EXPECT_EQ(error_key(d), "run.exchanges");
  d = minimal();
  d["participants"]["continuum"]["program"] = "surely_not_a_program_name";
  EXPECT_EQ(error_key(d), "participants.continuum.program");
  d = minimal();
  d["coupling"] = {{"exchange_intervall", 2}};
  EXPECT_EQ(error_key(d), "coupling.exchange_intervall");
  d = minimal();
  d["coupling"] = {{"scheme", "parallel"}};
  EXPECT_EQ(error_key(d), "coupling.scheme");
  d = minimal();
  d["participants"]["continuum"]["config"]["gravity_m_s2"] = {0, 0, -1};
  EXPECT_EQ(error_key(d), "participants.continuum.config.gravity_m_s2");
  d = minimal();
  d["participants"] = nlohmann::json::object();
  EXPECT_EQ(error_key(d), "participants");
}

TEST(Scenario, UnknownKeySuggestsTheClosestKnownKey) {
  auto d = minimal();
  d["run"]["exchangs"] = 2;
  try {
    (void)parse_scenario(d, "scenario.json", "");
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key_path(), "run.exchangs");
    EXPECT_NE(std::string(e.what()).find("did you mean \"exchanges\""), std::string::npos) << e.what();
  }
}

TEST(Scenario, EndpointInsteadOfProgram) {
  auto d = minimal();
  d["participants"]["continuum"] = {{"endpoint", "tcp://127.0.0.1:5555"}, {"config", nlohmann::json::object()}};
  const Scenario s = parse_scenario(d, "scenario.json", "");
  EXPECT_EQ(s.participants[0].endpoint, "tcp://127.0.0.1:5555");
  EXPECT_TRUE(s.participants[0].executable.empty());
  d["participants"]["continuum"]["endpoint"] = "localhost:5555";
  EXPECT_EQ(error_key(d), "participants.continuum.endpoint");
}

}  // namespace
}  // namespace dfc::coupler
