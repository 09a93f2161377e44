// Scenario reading (docs/running.md, "Scenarios"): defaults, gravity injection, program lookup,
// and errors that name the key path.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

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

TEST(Scenario, StopWhenAMonitorReachesAValue) {
  auto d = minimal();
  d["run"]["stop_when"] = {{"monitor", "dem_pile_displacement_m"}, {"at_least", 0.012}};
  const Scenario s = parse_scenario(d, "scenario.json", "");
  EXPECT_EQ(s.run.stop_monitor, std::optional<std::string>("dem_pile_displacement_m"));
  EXPECT_EQ(s.run.stop_monitor_at_least, 0.012);
  EXPECT_FALSE(s.run.stop_unbalanced_force_ratio);
  d["run"]["stop_when"] = {{"at_least", 0.012}};
  EXPECT_EQ(error_key(d), "run.stop_when.at_least");
  d["run"]["stop_when"] = {{"monitor", "pile_displacement_m"}, {"at_least", 0.012}};
  EXPECT_EQ(error_key(d), "run.stop_when.monitor");  // a column is "<slot>_<monitor>"
  d["run"]["stop_when"] = nlohmann::json::object();
  EXPECT_EQ(error_key(d), "run.stop_when.unbalanced_force_ratio");
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
  // No port: libzmq's connect threw "Invalid argument", reported as an internal error.
  for (const char* bad : {"tcp://127.0.0.1", "tcp://127.0.0.1:", "tcp://:5555", "tcp://127.0.0.1:0", "tcp://127.0.0.1:65536", "ipc://"}) {
    d["participants"]["continuum"]["endpoint"] = bad;
    EXPECT_EQ(error_key(d), "participants.continuum.endpoint") << bad;
  }
}

// Issue 20: bounds that `check` must apply because `run` depends on them.
TEST(Scenario, DurationsStepsAndTimeStepsAreBounded) {
  const auto with = [](const char* section, const char* key, const nlohmann::json& value) {
    auto d = minimal();
    d[section][key] = value;
    return error_key(d);
  };
  // 1e10 s overflowed steady_clock (an instant timeout); 1e300 printed a negative duration.
  EXPECT_EQ(with("run", "deadline_s", 1e10), "run.deadline_s");
  EXPECT_EQ(with("run", "deadline_s", 1e300), "run.deadline_s");
  EXPECT_EQ(with("run", "startup_timeout_s", 1e10), "run.startup_timeout_s");
  EXPECT_EQ(with("run", "deadline_s", 1800), "(no error)");
  // More steps per exchange than one advance may take passed check, then spun or failed at run time.
  EXPECT_EQ(with("coupling", "exchange_interval", 2'000'000'000), "coupling.exchange_interval");
  EXPECT_EQ(with("coupling", "continuum_steps_per_exchange", 2'000'000'000), "coupling.continuum_steps_per_exchange");
  EXPECT_EQ(with("coupling", "exchange_interval", 1'000'000'000), "(no error)");
  EXPECT_EQ(with("coupling", "dt_s", 1e-300), "coupling.dt_s");
  EXPECT_EQ(with("coupling", "dt_s", 1e-7), "(no error)");
}

/// A wait of run.* declared in seconds: `fallback` by default, a positive
/// value taken, a bad one (0, negative, beyond 1e6 s, not a number) refused naming the key.
void expect_declared_wait(const std::string& key, double fallback, double RunSpec::*field) {
  EXPECT_DOUBLE_EQ(parse_scenario(minimal(), "scenario.json", "").run.*field, fallback) << key;
  auto d = minimal();
  d["run"][key] = 2.5;
  EXPECT_DOUBLE_EQ(parse_scenario(d, "scenario.json", "").run.*field, 2.5) << key;
  for (const nlohmann::json& bad : {nlohmann::json(0), nlohmann::json(-1), nlohmann::json(1e10), nlohmann::json("10")}) {
    d["run"][key] = bad;
    try {
      (void)parse_scenario(d, "scenario.json", "");
      ADD_FAILURE() << key << " " << bad.dump() << " was accepted";
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.key_path(), "run." + key) << bad.dump();
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

// Issue 42: run.hang_timeout_s, how long a server may answer neither its
// request nor a heartbeat ping, is a declared key: 10 s by default.
TEST(Scenario, HangTimeoutIsDeclaredPositiveAndTenSecondsByDefault) { expect_declared_wait("hang_timeout_s", 10.0, &RunSpec::hang_timeout_s); }

// Issue 42: run.stall_timeout_s, how long a server's pongs may say the same
// progress (SPEC.md §9.1, 1.8), is a declared key: 120 s by default.
TEST(Scenario, StallTimeoutIsDeclaredPositiveAndTwoMinutesByDefault) {
  expect_declared_wait("stall_timeout_s", 120.0, &RunSpec::stall_timeout_s);
}

TEST(Scenario, NamesAndOutputFoldersThatWouldOverwriteInputsAreRefused) {
  auto d = minimal();
  for (const char* name : {"..", ".", "a/b", ""}) {
    d["name"] = name;
    EXPECT_EQ(error_key(d), "name") << name;
  }
  d = minimal();
  const auto cwd = std::filesystem::current_path();
  for (const std::string& directory : {std::string(""), std::string("."), std::string("./"), std::string(".."), cwd.string(), std::string("/")}) {
    d["output"] = {{"directory", directory}};
    EXPECT_EQ(error_key(d), "output.directory") << "'" << directory << "'";
  }
  // The scenario file's own folder: its scenario.json would be overwritten.
  const auto inputs = std::filesystem::temp_directory_path() / "dfc_scenario_inputs";
  d["output"] = {{"directory", inputs.string()}};
  try {
    (void)parse_scenario(d, inputs / "scenario.json", "");
    ADD_FAILURE() << "the scenario's folder was accepted as output.directory";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key_path(), "output.directory");
  }
  // A run's own record (DIR/scenario.json, read by --resume) names its folder by design.
  EXPECT_NO_THROW((void)parse_scenario(d, inputs / "scenario.json", "", ScenarioFileRole::run_record));
  d["output"] = {{"directory", "results/mine"}};
  EXPECT_EQ(error_key(d), "(no error)");
}

class ScenarioFile : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = std::filesystem::temp_directory_path() / ("dfc_scenario_file_" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder_);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  std::filesystem::path write(const std::string& text) {
    const auto path = folder_ / "scenario.json";
    std::ofstream(path) << text;
    return path;
  }

  /// The key path of the ConfigError, or "user error: <message>".
  static std::string load_error(const std::filesystem::path& path) {
    try {
      (void)load_scenarios(path, "");
    } catch (const ConfigError& e) {
      return e.key_path();
    } catch (const UserError& e) {
      return std::string("user error: ") + e.what();
    }
    return "(no error)";
  }

  std::filesystem::path folder_;
};

TEST_F(ScenarioFile, AnIncludedFileIsTheBaseTheIncludingObjectPatches) {
  // A shared parameter set (scenario_includes.hpp): the included object, with
  // the including object's own keys on top; nested includes resolve relative
  // to the file that names them.
  std::filesystem::create_directories(folder_ / "materials");
  std::ofstream(folder_ / "materials" / "rock.json") << R"({"law": "soft_bond", "emod_pa": 2.8e9, "friction": 0.5, "include": "gap.json"})";
  std::ofstream(folder_ / "materials" / "gap.json") << R"({"bond_gap_m": 6e-5, "friction": 0.3})";
  auto document = minimal();
  document["participants"]["continuum"]["config"] = {{"contact", {{"include", "materials/rock.json"}, {"friction", 0.7}}}};
  const std::vector<Scenario> scenarios = load_scenarios(write(document.dump()), "");
  ASSERT_EQ(scenarios.size(), 1u);
  const nlohmann::json contact = scenarios[0].participants[0].config.at("contact");
  EXPECT_EQ(contact, nlohmann::json::parse(R"({"law": "soft_bond", "emod_pa": 2.8e9, "friction": 0.7, "bond_gap_m": 6e-5})"));
  EXPECT_EQ(scenarios[0].document["participants"]["continuum"]["config"]["contact"], contact);  // the results keep the expanded text
  // A missing file and a file that includes itself name the "include" key.
  document["participants"]["continuum"]["config"]["contact"]["include"] = "materials/none.json";
  EXPECT_EQ(load_error(write(document.dump())), "participants.continuum.config.contact.include");
  std::ofstream(folder_ / "loop.json") << R"({"include": "loop.json"})";
  document["participants"]["continuum"]["config"]["contact"]["include"] = "loop.json";
  EXPECT_EQ(load_error(write(document.dump())), "participants.continuum.config.contact.include");
}

TEST_F(ScenarioFile, ANullNestedBelowTheIncludeRemovesTheIncludedKey) {
  // `"participants": {"continuum": {"config": {"contact": {"friction": null}}}}`
  // beside a top-level include removes that one included key (RFC 7386 merge
  // patch), however deep; a null with nothing to remove is dropped. The
  // objects between the include and the null have no include of their own:
  // merged level by level, the null was lost before it reached the key.
  auto base = minimal();
  base["participants"]["continuum"]["config"] = {{"contact", {{"law", "soft_bond"}, {"friction", 0.5}}}, {"damping", 0.7}};
  std::ofstream(folder_ / "base.json") << base.dump();
  const nlohmann::json document = {
      {"include", "base.json"},
      {"participants", {{"continuum", {{"config", {{"contact", {{"friction", nullptr}}}, {"unset", {{"deeper", nullptr}}}}}}}}}};
  const std::vector<Scenario> scenarios = load_scenarios(write(document.dump()), "");
  ASSERT_EQ(scenarios.size(), 1u);
  const nlohmann::json& config = scenarios[0].participants[0].config;
  EXPECT_EQ(config.at("contact"), nlohmann::json::parse(R"({"law": "soft_bond"})"));
  EXPECT_EQ(config.at("damping"), 0.7);
  EXPECT_EQ(config.at("unset"), nlohmann::json::object());  // its null removed nothing and is gone
}

TEST_F(ScenarioFile, DuplicateKeysAreRefusedNamingThem) {
  std::string text = minimal().dump();
  text.insert(text.size() - 1, R"(,"name":"again")");
  EXPECT_EQ(load_error(write(text)), "name");
}

TEST_F(ScenarioFile, NumberBeyondADoubleIsAKeyedError) {
  auto document = minimal();
  document["gravity"] = {{"g_level", 1}};
  std::string text = document.dump();
  text.replace(text.find(R"("g_level":1)"), 11, R"("g_level":1e999)");
  EXPECT_EQ(load_error(write(text)), "gravity.g_level");
}

TEST_F(ScenarioFile, DeepNestingIsAKeyedErrorNotACrash) {
  std::string text = minimal().dump();
  text.insert(text.size() - 1, R"(,"_note":)" + std::string(400'000, '[') + std::string(400'000, ']'));
  EXPECT_EQ(load_error(write(text)).rfind("_note[0]", 0), 0u);
}

TEST_F(ScenarioFile, FoldersDevicesAndHugeFilesAreRefusedBeforeReading) {
  EXPECT_NE(load_error(folder_).find("is a directory"), std::string::npos) << load_error(folder_);
  EXPECT_NE(load_error("/dev/zero").find("not a regular file"), std::string::npos) << load_error("/dev/zero");
  const auto huge = folder_ / "huge.json";
  std::ofstream(huge).close();
  std::filesystem::resize_file(huge, kMaxScenarioBytes + 1);  // sparse: costs no disk
  EXPECT_NE(load_error(huge).find("limited to 64 MiB"), std::string::npos) << load_error(huge);
}

}  // namespace
}  // namespace dfc::coupler
