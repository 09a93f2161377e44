#pragma once
// Scenario: the declarative JSON that describes one run (README, "Scenarios").
//
// The coupler validates the top level itself; each participant's "config"
// section is validated by the server that receives it (protocol `configure`,
// BAD_CONFIG names the key path, the coupler prefixes the section's path), so
// a third-party server validates its own section with no coupler change.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dfc/common/sections/scenario_sections.hpp"

namespace dfc::coupler {

inline constexpr int kScenarioSchemaVersion = sections::kScenarioSchemaVersion;
/// Largest scenario file read: scenarios are a few kB; this refuses a mistaken
/// path (a data dump) before it is read into memory.
inline constexpr std::uintmax_t kMaxScenarioBytes = std::uintmax_t(64) << 20;

/// One solver process the coupler talks to. The slot decides the role:
/// "dem" is the side driven by interface velocities (accepts_interface),
/// "continuum" the side that provides the interface (provides_interface).
struct ParticipantSpec {
  std::string slot;                       ///< "dem" or "continuum"
  std::string program;                    ///< as written in the scenario
  std::filesystem::path executable;       ///< resolved path (empty when connecting to an endpoint)
  std::vector<std::string> args;          ///< extra command-line arguments (with mpi_ranks > 1: the launcher's, then the program and its own)
  std::string endpoint;                   ///< connect here instead of starting a process
  nlohmann::json config;                  ///< the section sent in `configure` (gravity injected)
  std::filesystem::path key_file;         ///< with endpoint: that server's key file (SPEC.md §2.1); empty: none
  std::int64_t mpi_ranks = 1;             ///< processes of a DEM started under MPI (executable is then the launcher)
  [[nodiscard]] std::string key_path() const { return "participants." + slot; }
};

struct CouplingSpec {
  std::int64_t exchange_interval = 1;            ///< DEM steps per exchange (k)
  std::int64_t continuum_steps_per_exchange = 1; ///< continuum steps covering the same time (m)
  std::optional<double> dt_s;                    ///< DEM (or single participant) step; default: the server's suggestion
  double force_balance_tolerance = 1e-9;         ///< relative, see SPEC.md §6.3
};

struct RunSpec {
  std::int64_t exchanges = 1;    ///< number of exchanges (records) to run
  double deadline_s = 60.0;      ///< per request (SPEC.md §9)
  /// a server that answers neither its request nor a heartbeat ping this long is hung (SPEC.md §9.1)
  double hang_timeout_s = 10.0;
  /// a server whose heartbeat answers but whose progress stands still this long is hung (SPEC.md §9.1, 1.8)
  double stall_timeout_s = 120.0;
  double startup_timeout_s = 20; ///< for a started server to print DFC-LISTENING
  std::int64_t snapshot_every = 0;  ///< exchanges between snapshots; 0: initial and final only
  /// exchanges between coordinated checkpoints (docs/checkpoints.md); 0: none
  /// (then only a stop by signal writes one, where every server can)
  std::int64_t checkpoint_every = 0;
  /// run.stop_when.unbalanced_force_ratio: the run ends at the first exchange
  /// after which every participant's unbalanced_force_ratio monitor is at most
  /// this (equilibrium); `exchanges` is then the most it may take.
  std::optional<double> stop_unbalanced_force_ratio;
  std::int64_t stop_min_exchanges = 1;  ///< run.stop_when.min_exchanges: never before this many
  /// run.stop_when.monitor / at_least: the run also ends at the first exchange
  /// after which this time-series column (e.g. "dem_pile_displacement_m", a
  /// number monitor named "<slot>_<monitor>") is at least `stop_monitor_at_least`.
  std::optional<std::string> stop_monitor;
  double stop_monitor_at_least = 0.0;
};

struct Scenario {
  std::string name;
  std::string description;
  std::array<double, 3> gravity_m_s2{0.0, 0.0, 0.0};  ///< g · N along the direction
  double g_level = 1.0;
  std::vector<ParticipantSpec> participants;  ///< "dem" first if present, then "continuum"
  CouplingSpec coupling;
  RunSpec run;
  std::filesystem::path output_directory;
  nlohmann::json document;  ///< the whole scenario as read (written to the results)
  std::filesystem::path source;
  std::string variant_label;  ///< the label of this run in the file's "variants"; empty without

  [[nodiscard]] const ParticipantSpec* participant(std::string_view slot) const;
};

/// What a scenario file is: the user's input, or the copy a run keeps in its
/// results folder (DIR/scenario.json, read by `coupler run --resume DIR`).
/// A record names its own folder as output.directory by design, so the check
/// that the results do not overwrite the inputs' folder does not apply to it.
enum class ScenarioFileRole { input, run_record };

/// Reads and validates `path`: one run, or one per entry of "variants"
/// (scenario_variants.hpp), in order. `bin_dir` is where the project's
/// executables are (bare program names are looked up there first, then on
/// PATH). Throws dfc::ConfigError (key path + reason; a variant's error names
/// its label) or dfc::UserError.
[[nodiscard]] std::vector<Scenario> load_scenarios(const std::filesystem::path& path, const std::filesystem::path& bin_dir,
                                                   ScenarioFileRole role = ScenarioFileRole::input);

/// True for a name that can be one folder of a path: not empty, no '/', not
/// "." or ".." (scenario names and variant labels name results folders).
[[nodiscard]] bool is_single_folder_name(std::string_view name);

/// Why the results must not go to `directory`, or nullopt: it is empty, the
/// working folder or one above it, or the folder of `scenario_source`, where
/// the results (scenario.json, results.h5, logs/) would overwrite the user's files.
[[nodiscard]] std::optional<std::string> output_directory_problem(const std::filesystem::path& directory,
                                                                  const std::filesystem::path& scenario_source);

/// Same, from an already-parsed document.
[[nodiscard]] Scenario parse_scenario(const nlohmann::json& document, const std::filesystem::path& source, const std::filesystem::path& bin_dir,
                                      ScenarioFileRole role = ScenarioFileRole::input);

}  // namespace dfc::coupler
