#include "dfc/coupler/scenario.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/coupler/scenario_variants.hpp"

namespace dfc::coupler {

namespace {

namespace fs = std::filesystem;

bool is_executable(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
}

// Bare names: the project's bin directory first (so `dem_server` means ours),
// then PATH. Names with a slash: relative to the scenario file, then to the CWD.
std::optional<fs::path> resolve_program(const std::string& program, const fs::path& scenario_dir, const fs::path& bin_dir) {
  if (program.find('/') != std::string::npos) {
    for (const fs::path& base : {scenario_dir, fs::current_path()}) {
      const fs::path candidate = fs::path(program).is_absolute() ? fs::path(program) : base / program;
      if (is_executable(candidate)) return fs::absolute(candidate);
    }
    return std::nullopt;
  }
  if (!bin_dir.empty() && is_executable(bin_dir / program)) return bin_dir / program;
  if (const char* path = std::getenv("PATH")) {
    std::stringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':'))
      if (!dir.empty() && is_executable(fs::path(dir) / program)) return fs::path(dir) / program;
  }
  return std::nullopt;
}

ParticipantSpec read_participant(ConfigReader reader, const std::string& slot, const fs::path& scenario_dir, const fs::path& bin_dir,
                                 const std::array<double, 3>& gravity) {
  ParticipantSpec spec;
  spec.slot = slot;
  spec.endpoint = reader.string("endpoint", "");
  if (spec.endpoint.empty()) {
    spec.program = reader.string("program");
    const auto resolved = resolve_program(spec.program, scenario_dir, bin_dir);
    if (!resolved)
      reader.fail("program", "no executable '" + spec.program + "' found" +
                                 (spec.program.find('/') == std::string::npos ? " in " + bin_dir.string() + " or on PATH" : "") +
                                 "; name a built server (dem_server, fdm_server, rigid_continuum_server) or a path to a program that speaks protocol v1");
    spec.executable = *resolved;
  } else {
    if (reader.has("program")) reader.fail("program", "give either 'program' (start a server) or 'endpoint' (connect to a running one), not both");
    if (spec.endpoint.rfind("tcp://", 0) != 0 && spec.endpoint.rfind("ipc://", 0) != 0)
      reader.fail("endpoint", "expected a ZeroMQ endpoint such as \"tcp://127.0.0.1:5555\", got \"" + spec.endpoint + "\"");
  }
  if (reader.has("args")) spec.args = reader.strings("args");
  else reader.accept("args");
  const nlohmann::json& config = reader.raw("config");
  if (!config.is_object()) reader.fail("config", "expected an object: the section this server is configured with");
  spec.config = config;
  if (spec.config.contains("gravity_m_s2"))
    throw ConfigError(reader.key_path("config") + ".gravity_m_s2",
                      "gravity is set once for the whole model in the top-level 'gravity' object; remove it here");
  spec.config["gravity_m_s2"] = gravity;
  reader.finish();
  return spec;
}

}  // namespace

const ParticipantSpec* Scenario::participant(std::string_view slot) const {
  for (const auto& p : participants)
    if (p.slot == slot) return &p;
  return nullptr;
}

std::vector<Scenario> load_scenarios(const fs::path& path, const fs::path& bin_dir) {
  std::ifstream in(path);
  if (!in) throw UserError("cannot open scenario file '" + path.string() + "'; check the path");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw UserError("scenario '" + path.string() + "' is not valid JSON: " + e.what());
  }
  std::vector<Scenario> scenarios;
  for (const ScenarioVariant& variant : expand_variants(document)) {
    try {
      scenarios.push_back(parse_scenario(variant.document, path, bin_dir));
      scenarios.back().variant_label = variant.label;
    } catch (const ConfigError& e) {
      if (variant.label.empty()) throw;
      throw ConfigError(e.key_path(), "(variant \"" + variant.label + "\") " + e.reason());
    }
  }
  return scenarios;
}

Scenario parse_scenario(const nlohmann::json& document, const fs::path& source, const fs::path& bin_dir) {
  Scenario scenario;
  scenario.document = document;
  scenario.source = source;
  ConfigReader root(document, "");
  const std::int64_t schema = root.integer("schema_version", 1);  // required, >= 1
  if (schema != kScenarioSchemaVersion)
    root.fail("schema_version", "this coupler reads schema_version " + std::to_string(kScenarioSchemaVersion) + ", the file has " +
                                    std::to_string(schema));
  scenario.name = root.string("name");
  if (scenario.name.empty() || scenario.name.find('/') != std::string::npos)
    root.fail("name", "expected a non-empty name without '/', used for the results folder");
  scenario.description = root.string("description", "");

  // Gravity: g · N along a unit direction (virtual centrifuge, docs/theory/upscaling_and_pcrm.md §5).
  if (auto gravity = root.optional_child("gravity")) {
    const double g = gravity->number("g_m_s2", 9.81, Bounds{0.0});
    scenario.g_level = gravity->number("g_level", 1.0, Bounds{0.0, 1e5, true});
    const auto direction = gravity->vec3("direction", {0.0, 0.0, -1.0});
    const double norm = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
    if (!(norm > 0)) gravity->fail("direction", "expected a non-zero vector");
    for (int i = 0; i < 3; ++i) scenario.gravity_m_s2[std::size_t(i)] = g * scenario.g_level * direction[std::size_t(i)] / norm;
    gravity->finish();
  }

  const fs::path scenario_dir = source.has_parent_path() ? source.parent_path() : fs::current_path();
  ConfigReader participants = root.child("participants");
  for (const char* slot : {"dem", "continuum"})
    if (auto section = participants.optional_child(slot))
      scenario.participants.push_back(read_participant(*section, slot, scenario_dir, bin_dir, scenario.gravity_m_s2));
  participants.finish();
  if (scenario.participants.empty())
    throw ConfigError("participants", "a scenario needs at least one participant: 'dem', 'continuum' or both");

  if (auto coupling = root.optional_child("coupling")) {
    CouplingSpec& c = scenario.coupling;
    c.exchange_interval = coupling->integer("exchange_interval", 1, 1);
    c.continuum_steps_per_exchange = coupling->integer("continuum_steps_per_exchange", 1, 1);
    if (coupling->has("dt_s")) c.dt_s = coupling->positive("dt_s");
    else coupling->accept("dt_s");
    c.force_balance_tolerance = coupling->number("force_balance_tolerance", 1e-9, Bounds{0.0, 1.0, true});
    (void)coupling->choice("scheme", {"serial"}, "serial");
    coupling->finish();
  }

  ConfigReader run = root.child("run");
  scenario.run.exchanges = run.integer("exchanges", 1);
  scenario.run.deadline_s = run.positive("deadline_s", 60.0);
  scenario.run.startup_timeout_s = run.positive("startup_timeout_s", 20.0);
  scenario.run.snapshot_every = run.integer("snapshot_every", 0, 0);
  if (auto stop = run.optional_child("stop_when")) {
    scenario.run.stop_unbalanced_force_ratio = stop->number("unbalanced_force_ratio", Bounds{0.0, 1.0, true});
    if (!(*scenario.run.stop_unbalanced_force_ratio > 0.0)) stop->fail("unbalanced_force_ratio", "expected a ratio in (0, 1), e.g. 1e-3");
    scenario.run.stop_min_exchanges = stop->integer("min_exchanges", 1, 1);
    stop->finish();
  }
  run.finish();

  scenario.output_directory = fs::path("results") / scenario.name;
  if (auto output = root.optional_child("output")) {
    scenario.output_directory = output->string("directory", scenario.output_directory.string());
    output->finish();
  }
  root.finish();
  return scenario;
}

}  // namespace dfc::coupler
