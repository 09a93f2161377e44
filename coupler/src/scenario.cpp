#include "dfc/coupler/scenario.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/durations.hpp"
#include "dfc/common/echo.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/common/json_text.hpp"
#include "dfc/common/sections/scenario_sections.hpp"
#include "dfc/coupler/scenario_includes.hpp"
#include "dfc/coupler/scenario_variants.hpp"
#include "dfc/protocol/message.hpp"
#include "dfc/protocol/transport.hpp"

namespace dfc::coupler {

namespace {

namespace fs = std::filesystem;

static_assert(sections::kMaxStepsPerExchange == protocol::kMaxStepsPerAdvance,
              "the declared steps per exchange must be what one advance may take (SPEC.md §4)");

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

/// participants.<slot>.mpi_ranks and mpi_launcher: a DEM on N > 1 processes
/// is started as `launcher... -n N dem_server --mpi args...` (docs/determinism.md §3).
void read_mpi_launch(ConfigReader& reader, ParticipantSpec& spec, const fs::path& scenario_dir, const fs::path& bin_dir) {
  const std::int64_t ranks = reader.integer("mpi_ranks");
  if (ranks == 1) {
    if (reader.has("mpi_launcher")) (void)reader.strings("mpi_launcher");  // read, so that it is not refused as unknown; nothing to launch
    return;
  }
  if (spec.slot != "dem")
    reader.fail("mpi_ranks", "only the DEM (dem_server) runs on many processes; remove mpi_ranks from participants." + spec.slot);
  if (!spec.endpoint.empty())
    reader.fail("mpi_ranks", "a server the coupler connects to (endpoint) was started by hand: start it as 'mpiexec -n " + std::to_string(ranks) +
                                 " dem_server --mpi' and remove mpi_ranks here");
  std::vector<std::string> launcher = reader.has("mpi_launcher") ? reader.strings("mpi_launcher") : std::vector<std::string>{"mpiexec", "--oversubscribe"};
  if (launcher.empty() || launcher.front().empty()) reader.fail("mpi_launcher", "name the launcher, e.g. [\"mpiexec\"] or [\"srun\"]");
  const auto resolved = resolve_program(launcher.front(), scenario_dir, bin_dir);
  if (!resolved)
    reader.fail(reader.has("mpi_launcher") ? "mpi_launcher" : "mpi_ranks",
                "no MPI launcher '" + launcher.front() + "' found on PATH; install OpenMPI (Debian: openmpi-bin libopenmpi-dev, which ./vc installs) "
                "and build again, or name your MPI's launcher in mpi_launcher");
  std::vector<std::string> args(launcher.begin() + 1, launcher.end());
  args.insert(args.end(), {"-n", std::to_string(ranks), spec.executable.string(), "--mpi"});
  args.insert(args.end(), spec.args.begin(), spec.args.end());
  spec.args = std::move(args);
  spec.executable = *resolved;
  spec.mpi_ranks = ranks;
}

ParticipantSpec read_participant(ConfigReader reader, const std::string& slot, const fs::path& scenario_dir, const fs::path& bin_dir,
                                 const std::array<double, 3>& gravity) {
  ParticipantSpec spec;
  spec.slot = slot;
  spec.endpoint = reader.has("endpoint") ? reader.string("endpoint") : std::string();
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
    if (const auto problem = protocol::endpoint_problem(spec.endpoint)) reader.fail("endpoint", *problem);
    if (reader.has("key_file")) {
      const fs::path key_file = reader.string("key_file");
      spec.key_file = key_file.is_absolute() ? key_file : scenario_dir / key_file;
    }
  }
  if (spec.endpoint.empty() && reader.has("key_file"))
    reader.fail("key_file", "the coupler makes the keys of the servers it starts (program) itself, one per run; key_file names the key of a "
                            "server started by hand (endpoint): remove it here");
  if (reader.has("args")) spec.args = reader.strings("args");
  read_mpi_launch(reader, spec, scenario_dir, bin_dir);
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

/// Reads the scenario file's text, refusing what is not a sensible scenario
/// file before reading it: a folder, a device such as /dev/zero (endless), a file
/// beyond kMaxScenarioBytes.
std::string read_scenario_text(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw UserError("cannot open scenario file '" + path.string() + "'; check the path");
  if (fs::is_directory(status)) throw UserError("scenario '" + path.string() + "' is a directory; give the path of a scenario JSON file in it");
  if (!fs::is_regular_file(status))
    throw UserError("scenario '" + path.string() + "' is not a regular file (a device, pipe or socket); give the path of a scenario JSON file");
  const auto size = fs::file_size(path, ec);
  if (!ec && size > kMaxScenarioBytes)
    throw UserError("scenario '" + path.string() + "' has " + std::to_string(size) + " bytes; scenario files are limited to " +
                    std::to_string(kMaxScenarioBytes >> 20) + " MiB (large data such as particle lists belong in the server's own input files)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError("cannot open scenario file '" + path.string() + "'; check the path");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

const ParticipantSpec* Scenario::participant(std::string_view slot) const {
  for (const auto& p : participants)
    if (p.slot == slot) return &p;
  return nullptr;
}

bool is_single_folder_name(std::string_view name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string_view::npos && name.find('\0') == std::string_view::npos;
}

std::optional<std::string> output_directory_problem(const fs::path& directory, const fs::path& scenario_source) {
  if (directory.empty()) return "expected a folder for the results, got an empty path; leave the key out to use results/<name>";
  std::error_code ec;
  fs::path target = fs::weakly_canonical(fs::absolute(directory), ec);
  if (ec) return std::nullopt;  // unresolvable paths fail, with their reason, when the folder is created
  if (!target.has_filename()) target = target.parent_path();  // "dir/" names the same folder as "dir"
  const fs::path working = fs::weakly_canonical(fs::current_path(), ec);
  // The working folder or one above it: results.h5, scenario.json and logs/
  // would land among (and overwrite) the user's own files.
  const std::string named = echoed(directory.string(), kMaxEchoedPathBytes);  // an lvalue: "'" + a temporary trips GCC 12's -Wrestrict
  if (std::mismatch(target.begin(), target.end(), working.begin(), working.end()).first == target.end())
    return "'" + named + "' is the working folder or one above it; the results (scenario.json, results.h5, logs/) would overwrite files "
           "there: name a folder of their own, e.g. results/<name>";
  if (!scenario_source.empty()) {
    const fs::path inputs = fs::weakly_canonical(fs::absolute(scenario_source), ec).parent_path();
    if (!ec && target == inputs)
      return "'" + named + "' is the folder of the scenario file; the results (scenario.json, results.h5, logs/) would overwrite "
             "inputs there: name a folder of their own, e.g. results/<name>";
  }
  return std::nullopt;
}

std::vector<Scenario> load_scenarios(const fs::path& path, const fs::path& bin_dir, ScenarioFileRole role) {
  const auto load = [](const fs::path& file) {
    try {
      return parse_json_text(read_scenario_text(file), JsonTextLimits{.reject_duplicate_keys = true});
    } catch (const JsonTextError& e) {
      if (e.kind() == JsonTextError::Kind::syntax) throw UserError("scenario '" + file.string() + "' is not valid JSON: " + e.what());
      throw ConfigError(e.key_path(), e.reason());
    }
  };
  const nlohmann::json document = resolve_includes(load(path), path.has_parent_path() ? path.parent_path() : fs::path("."), load);
  std::vector<Scenario> scenarios;
  for (const ScenarioVariant& variant : expand_variants(document)) {
    try {
      scenarios.push_back(parse_scenario(variant.document, path, bin_dir, role));
      scenarios.back().variant_label = variant.label;
    } catch (const ConfigError& e) {
      if (variant.label.empty()) throw;
      throw ConfigError(e.key_path(), "(variant \"" + echoed(variant.label) + "\") " + e.reason());
    }
  }
  return scenarios;
}

Scenario parse_scenario(const nlohmann::json& document, const fs::path& source, const fs::path& bin_dir, ScenarioFileRole role) {
  Scenario scenario;
  scenario.document = document;
  scenario.source = source;
  ConfigReader root(document, "", sections::scenario());
  const std::int64_t schema = root.integer("schema_version");
  if (schema != kScenarioSchemaVersion)
    root.fail("schema_version", "this coupler reads schema_version " + std::to_string(kScenarioSchemaVersion) + ", the file has " +
                                    std::to_string(schema));
  scenario.name = root.string("name");
  if (!is_single_folder_name(scenario.name))
    root.fail("name", "expected a non-empty name without '/' that is not '.' or '..': it names the results folder results/<name>");
  scenario.description = root.string("description");

  // Gravity: g · N along a unit direction (virtual centrifuge, docs/theory/upscaling_and_pcrm.md §5).
  if (auto gravity = root.optional_child("gravity")) {
    const double g = gravity->number("g_m_s2");
    scenario.g_level = gravity->number("g_level");
    const auto direction = gravity->vec3("direction");
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
    // Each exchange is one advance per side, which takes at most kMaxStepsPerAdvance steps (SPEC.md §4).
    c.exchange_interval = coupling->integer("exchange_interval");
    c.continuum_steps_per_exchange = coupling->integer("continuum_steps_per_exchange");
    if (coupling->has("dt_s")) c.dt_s = coupling->number("dt_s");
    c.force_balance_tolerance = coupling->number("force_balance_tolerance");
    (void)coupling->string("scheme");
    coupling->finish();
  }

  ConfigReader run = root.child("run");
  scenario.run.exchanges = run.integer("exchanges");
  scenario.run.deadline_s = run.number("deadline_s");
  scenario.run.hang_timeout_s = run.number("hang_timeout_s");
  scenario.run.stall_timeout_s = run.number("stall_timeout_s");
  scenario.run.startup_timeout_s = run.number("startup_timeout_s");
  scenario.run.snapshot_every = run.integer("snapshot_every");
  scenario.run.checkpoint_every = run.integer("checkpoint_every");
  if (auto stop = run.optional_child("stop_when")) {
    if (stop->has("unbalanced_force_ratio")) {
      scenario.run.stop_unbalanced_force_ratio = stop->number("unbalanced_force_ratio");
      if (!(*scenario.run.stop_unbalanced_force_ratio > 0.0)) stop->fail("unbalanced_force_ratio", "expected a ratio in (0, 1), e.g. 1e-3");
    }
    if (stop->has("monitor")) {
      scenario.run.stop_monitor = stop->string("monitor");
      if (!scenario.run.stop_monitor->starts_with("dem_") && !scenario.run.stop_monitor->starts_with("continuum_"))
        stop->fail("monitor", "expected a time-series column \"<slot>_<monitor>\" of a number monitor, e.g. \"dem_pile_displacement_m\"");
      scenario.run.stop_monitor_at_least = stop->number("at_least");
    } else {
      if (stop->has("at_least")) stop->fail("at_least", "\"at_least\" is the threshold of \"monitor\"; name the monitor too");
    }
    if (!scenario.run.stop_unbalanced_force_ratio && !scenario.run.stop_monitor)
      stop->fail("unbalanced_force_ratio", "stop_when needs \"unbalanced_force_ratio\" (equilibrium) or \"monitor\" with \"at_least\", or both");
    scenario.run.stop_min_exchanges = stop->integer("min_exchanges");
    stop->finish();
  }
  run.finish();

  scenario.output_directory = fs::path("results") / scenario.name;
  if (auto output = root.optional_child("output")) {
    if (output->has("directory")) scenario.output_directory = output->string("directory");
    // A run record lives in the folder it names (that is where --resume reads it).
    const fs::path inputs = role == ScenarioFileRole::input ? source : fs::path();
    if (const auto problem = output_directory_problem(scenario.output_directory, inputs)) output->fail("directory", *problem);
    output->finish();
  }
  root.finish();
  return scenario;
}

}  // namespace dfc::coupler
