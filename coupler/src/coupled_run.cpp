#include "dfc/coupler/coupled_run.hpp"


#include <algorithm>
#include <cmath>
#include <iostream>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <string_view>
#include <utility>

#include <zmq.hpp>

#include "dfc/common/durations.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/common/json_text.hpp"
#include "dfc/common/temporary_folder.hpp"
#include "dfc/common/version.hpp"
#include "dfc/coupler/progress_line.hpp"
#include "dfc/coupler/results_writer.hpp"
#include "dfc/coupler/run_checkpoint.hpp"
#include "dfc/coupler/run_recorder.hpp"
#include "dfc/coupler/serial_coupling_scheme.hpp"
#include "dfc/coupler/snapshot_estimate.hpp"
#include "dfc/protocol/message.hpp"
#include "dfc/protocol/monitor_units.hpp"
#include "dfc/protocol/progress_monitors.hpp"
#include "dfc/protocol/run_key_file.hpp"

namespace dfc::coupler {

namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double scalar_monitor(const nlohmann::json& monitors, const char* name) {
  const auto it = monitors.find(name);
  // + 0.0 turns a negative zero into 0, so summaries never print "-0 N".
  return it != monitors.end() && it->is_number() ? it->get<double>() + 0.0 : kNaN;
}

/// True when every participant reported an unbalanced_force_ratio at most
/// `limit` (a participant that reports none, or NaN, is not in equilibrium).
/// The largest unbalanced_force_ratio over the participants (NaN if one lacks it).
double largest_unbalanced_ratio(const std::map<std::string, nlohmann::json>& monitors) {
  double largest = 0.0;
  for (const auto& [slot, values] : monitors) {
    const double ratio = scalar_monitor(values, "unbalanced_force_ratio");
    if (!(ratio <= largest)) largest = ratio;  // NaN propagates
  }
  return largest;
}

bool every_in_equilibrium(const std::map<std::string, nlohmann::json>& monitors, double limit) {
  return !monitors.empty() && largest_unbalanced_ratio(monitors) <= limit;
}

/// True when the number monitor behind time-series column `column`
/// ("<slot>_<monitor>", run.stop_when.monitor) is at least `threshold`.
bool monitor_reached(const std::map<std::string, nlohmann::json>& monitors, const std::string& column, double threshold) {
  for (const auto& [slot, values] : monitors)
    if (column.starts_with(slot + "_") && scalar_monitor(values, column.c_str() + slot.size() + 1) >= threshold) return true;
  return false;
}

std::optional<double> info_number(const nlohmann::json& info, const char* key) {
  const auto it = info.find(key);
  if (it == info.end() || !it->is_number()) return std::nullopt;
  return it->get<double>();
}

ExchangeTiming choose_timing(const Scenario& scenario, Participant* dem, Participant* continuum) {
  ExchangeTiming timing;
  const auto& c = scenario.coupling;
  const auto check_stable = [](Participant& p, double dt, const std::string& key, const std::string& fix) {
    const auto dt_max = info_number(p.configured_info(), "dt_max");
    if (dt_max && dt > *dt_max * (1.0 + 1e-12)) {
      std::ostringstream reason;
      reason << p.spec().slot << " would run at dt = " << dt << " s but " << p.spec().program << " is stable only up to " << *dt_max
             << " s; " << fix;
      throw ConfigError(key, reason.str());
    }
  };
  if (dem != nullptr) {
    const auto suggested = info_number(dem->configured_info(), "dt_suggested");
    if (!c.dt_s && !suggested)
      throw ConfigError("coupling.dt_s", "the dem server suggested no time step; set coupling.dt_s");
    timing.dt_dem = c.dt_s ? *c.dt_s : *suggested;
    timing.dem_steps_per_exchange = c.exchange_interval;
    check_stable(*dem, timing.dt_dem, c.dt_s ? "coupling.dt_s" : "participants.dem.config", "lower coupling.dt_s");
  }
  if (continuum != nullptr) {
    timing.continuum_steps_per_exchange = c.continuum_steps_per_exchange;
    if (dem != nullptr) {
      timing.dt_continuum = timing.exchange_duration() / double(timing.continuum_steps_per_exchange);
    } else {
      const auto suggested = info_number(continuum->configured_info(), "dt_suggested");
      if (!c.dt_s && !suggested) throw ConfigError("coupling.dt_s", "the continuum server suggested no time step; set coupling.dt_s");
      timing.dt_continuum = c.dt_s ? *c.dt_s : *suggested;
    }
    const auto dt_max = info_number(continuum->configured_info(), "dt_max");
    if (dem != nullptr) {
      const std::string fix = dt_max ? "raise coupling.continuum_steps_per_exchange to at least " +
                                           std::to_string(static_cast<long long>(std::ceil(timing.exchange_duration() / *dt_max))) +
                                           " or enable the continuum's mass scaling"
                                     : "";
      check_stable(*continuum, timing.dt_continuum, "coupling.continuum_steps_per_exchange", fix);
    } else {
      check_stable(*continuum, timing.dt_continuum, "coupling.dt_s", "lower coupling.dt_s or leave it out to use the server's suggestion");
    }
  }
  return timing;
}

/// MemAvailable of /proc/meminfo in bytes, or nullopt where it cannot be read.
std::optional<double> available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string name;
  double kib = 0.0;
  std::string unit;
  while (meminfo >> name >> kib >> unit)
    if (name == "MemAvailable:") return kib * 1024.0;
  return std::nullopt;
}

/// Refuses, at configure time and with the key, a model whose snapshots the
/// coupler could not take: an array over the protocol limit, or more memory
/// than the machine has (snapshot_estimate.hpp: every array the DEM section's
/// snapshot block asks for, from the counts the server reports). Otherwise a
/// 1e7-particle bed passed `check` and died with a bare std::bad_alloc at the
/// first snapshot, and a bonded bed of 3.3 million particles at its first
/// snapshot with bond arrays over the limit. Continua stay far smaller.
void check_snapshot_memory(Participant& p, milliseconds deadline) {
  if (!p.has(protocol::capability::snapshot)) return;
  nlohmann::json monitors;
  try {
    monitors = p.client().query(deadline);
  } catch (const std::exception& e) {
    p.fail(e, "reporting its configured state (query)");
  }
  check_snapshot_estimate(estimate_dem_snapshot(p.spec().config, monitors, p.spec().key_path()), double(protocol::Limits{}.max_array_bytes),
                          available_memory_bytes());
}

/// The participants of the dem and the continuum slot (null where the scenario has none).
std::pair<Participant*, Participant*> by_slot(const std::vector<std::unique_ptr<Participant>>& participants) {
  std::pair<Participant*, Participant*> slots{nullptr, nullptr};
  for (const auto& p : participants) (p->spec().slot == "dem" ? slots.first : slots.second) = p.get();
  return slots;
}

/// Per slot, the monitors its server asks the coupler to show (SPEC.md §4.2,
/// configure's info.progress_monitors), in participant order.
using ProgressMonitors = std::vector<std::pair<std::string, std::vector<protocol::ProgressMonitor>>>;

ProgressMonitors progress_monitors(const std::vector<std::unique_ptr<Participant>>& participants) {
  ProgressMonitors shown;
  for (const auto& p : participants) {
    try {
      if (auto entries = protocol::parse_progress_monitors(p->configured_info()); !entries.empty())
        shown.emplace_back(p->spec().slot, std::move(entries));
    } catch (const std::invalid_argument& e) {
      p->fail(e, "reading its configured.info (SPEC.md §4.2)");
    }
  }
  return shown;
}

/// "label value unit, ..." of every slot's progress monitors in `monitors` (the last exchange's).
std::string shown_monitors(const ProgressMonitors& progress, const std::map<std::string, nlohmann::json>& monitors) {
  std::string shown;
  for (const auto& [slot, entries] : progress) {
    const auto slot_monitors = monitors.find(slot);
    if (slot_monitors == monitors.end()) continue;
    const std::string text = protocol::format_progress(entries, slot_monitors->second);
    if (!text.empty()) shown += (shown.empty() ? "" : ", ") + text;
  }
  return shown;
}

/// Starts and greets the participants; configures them; throws on the first problem.
/// The servers started get `run_keys` (SPEC.md §2.1).
std::vector<std::unique_ptr<Participant>> start_participants(zmq::context_t& context, const Scenario& scenario, const fs::path& log_dir,
                                                            StopRequest& stop, const protocol::RunKeyFile& run_keys) {
  std::vector<std::unique_ptr<Participant>> participants;
  for (const auto& spec : scenario.participants) {
    participants.push_back(
        std::make_unique<Participant>(context, spec, log_dir, milliseconds_from_seconds(scenario.run.startup_timeout_s),
                                      protocol::HangTimeouts{milliseconds_from_seconds(scenario.run.hang_timeout_s),
                                                             milliseconds_from_seconds(scenario.run.stall_timeout_s)},
                                      stop, &run_keys));
    participants.back()->hello(milliseconds(10'000));
  }
  const bool coupled = participants.size() == 2;
  for (auto& p : participants) {
    p->configure(milliseconds_from_seconds(scenario.run.deadline_s));
    check_snapshot_memory(*p, milliseconds_from_seconds(scenario.run.deadline_s));
    if (scenario.run.checkpoint_every > 0 && !p->has(protocol::capability::checkpoint))
      throw ConfigError("run.checkpoint_every", "'" + p->spec().program + "' (" + p->info().solver_name + "), the " + p->spec().slot +
                                                    " server, lacks capability 'checkpoint' (SPEC.md §4.7): it cannot write its state, so this run "
                                                    "could not be resumed; remove run.checkpoint_every or use a server that has it");
    if (coupled) {
      const char* needed = p->spec().slot == "dem" ? protocol::capability::accepts_interface : protocol::capability::provides_interface;
      if (!p->has(needed))
        throw ConfigError(p->spec().key_path() + ".program",
                          "'" + p->spec().program + "' (" + p->info().solver_name + "), as configured, lacks capability '" + needed +
                              "' that the " + p->spec().slot + " slot of a coupled run needs (check its coupling settings)");
    }
  }
  return participants;
}

void write_snapshots(ResultsWriter& writer, std::vector<std::unique_ptr<Participant>>& participants, double time, milliseconds deadline) {
  for (auto& p : participants) {
    if (!p->has(protocol::capability::snapshot)) continue;
    protocol::Message reply;
    try {
      reply = p->client().snapshot(deadline);
    } catch (const std::exception& e) {
      p->fail(e, "taking a snapshot");
    }
    writer.write_snapshot(p->spec().slot, reply.step.value_or(0), time, reply.body.value("kind", "unknown"), reply.arrays);
  }
}

/// Step 3: the interface mesh goes from the continuum to the DEM
/// (docs/theory/coupling.md §2). Returns its node count (0 for an uncoupled run).
std::int64_t install_interface(Participant* dem, Participant* continuum, milliseconds deadline) {
  if (dem == nullptr || continuum == nullptr) return 0;
  protocol::InterfaceMesh interface;
  try {
    interface = continuum->client().get_interface(deadline);
  } catch (const std::exception& e) {
    continuum->fail(e, "sending its interface mesh");
  }
  try {
    dem->client().set_interface(interface, deadline);
  } catch (const std::exception& e) {
    dem->fail(e, "installing the interface mesh as coupling walls");
  }
  return interface.node_count();
}

/// Throws UserError when `resumed` cannot continue with these participants.
void check_can_resume(const CouplerCheckpoint& resumed, const Scenario& scenario, const std::vector<std::unique_ptr<Participant>>& participants) {
  RunCheckpoints::check_resumable(resumed, scenario, participants);
  for (const auto& p : participants)
    if (!p->has(protocol::capability::checkpoint))
      throw UserError("cannot resume: the " + p->spec().slot + " server '" + p->spec().program + "' lacks capability 'checkpoint'");
}

/// The results file's `versions` attribute: the coupler's, the protocol's and each server's.
nlohmann::json program_versions(const std::vector<std::unique_ptr<Participant>>& participants) {
  nlohmann::json versions = {{"coupler", {{"name", "coupler"}, {"version", std::string(project_version())}}},
                             {"protocol", protocol::version_string()}};
  for (const auto& p : participants)
    versions[p->spec().slot] = {{"name", p->info().solver_name},
                                {"version", p->info().solver_version},
                                {"protocol", p->info().protocol_version},
                                {"configured", p->configured_info()}};
  return versions;
}

/// Each server's walls by name (configure's info.walls, dem_server) into the
/// results file, in the order of a snapshot's wall_facet_wall index; the DEM
/// of a coupled run has the coupling surface after them (install_interface).
void name_walls(ResultsWriter& writer, const std::vector<std::unique_ptr<Participant>>& participants, bool coupling_surface) {
  for (const auto& p : participants) {
    const auto walls = p->configured_info().find("walls");
    if (walls == p->configured_info().end() || !walls->is_array()) continue;
    std::vector<std::string> names;
    for (const auto& name : *walls) names.push_back(name.is_string() ? name.get<std::string>() : name.dump());
    if (coupling_surface && p->spec().slot == "dem") names.emplace_back("coupling surface");
    writer.name_walls(p->spec().slot, names);
  }
}

/// Creates the run's folder and its logs folder; a new run also gets a copy of its scenario there.
void prepare_output_folder(const fs::path& out_dir, const fs::path& log_dir, const Scenario& scenario, bool resume) {
  std::error_code ec;
  fs::create_directories(log_dir, ec);
  if (ec) throw UserError("cannot create the output folder '" + log_dir.string() + "': " + ec.message() + "; choose another with --out");
  if (!resume) {  // a resumed run reads its scenario from this copy
    std::ofstream copy(out_dir / "scenario.json");
    copy << readable_json(scenario.document) << "\n";
  }
}

/// Per slot: configure's info.monitor_units (null for a server that declares none).
std::map<std::string, nlohmann::json> declared_units(const std::vector<std::unique_ptr<Participant>>& participants) {
  std::map<std::string, nlohmann::json> units;
  for (const auto& p : participants) units[p->spec().slot] = p->configured_info().value(protocol::monitor_units_key, nlohmann::json());
  return units;
}

/// Per slot: {name, version} of the server, which a checkpoint records.
nlohmann::json solver_names(const std::vector<std::unique_ptr<Participant>>& participants) {
  nlohmann::json solvers = nlohmann::json::object();
  for (const auto& p : participants) solvers[p->spec().slot] = {{"name", p->info().solver_name}, {"version", p->info().solver_version}};
  return solvers;
}

/// Checkpoints need every server's capability; without run.checkpoint_every a
/// stop by signal still writes one where they have it.
bool every_can_checkpoint(const std::vector<std::unique_ptr<Participant>>& participants) {
  return std::all_of(participants.begin(), participants.end(), [](const auto& p) { return p->has(protocol::capability::checkpoint); });
}

/// The run's first line in the log.
void announce_run(std::ostream& log, const Scenario& scenario, const ExchangeTiming& timing, const std::optional<CouplerCheckpoint>& resumed,
                  const Participant* dem, const Participant* continuum, std::int64_t n_nodes) {
  log << (resumed ? "Resuming run '" : "Run '") << scenario.name << "'";
  if (resumed) log << " after exchange " << resumed->loop.coupling.exchanges_done;
  log << ": " << scenario.run.exchanges << " exchanges";
  if (dem) log << ", " << timing.dem_steps_per_exchange << " DEM step(s) of " << timing.dt_dem << " s";
  if (continuum) log << ", " << timing.continuum_steps_per_exchange << " continuum step(s) of " << timing.dt_continuum << " s";
  if (dem && continuum) log << ", " << n_nodes << " interface nodes";
  log << " each." << std::endl;  // flushed: a supervisor reading the log sees the run start
}

/// What the exchanges of a started run use (run_scenario sets it up).
struct StartedRun {
  const Scenario& scenario;
  const RunOptions& options;
  std::vector<std::unique_ptr<Participant>>& participants;
  StopRequest& stop;
  milliseconds deadline;
  ResultsWriter& writer;
  RunRecorder& recorder;
  const RunCheckpoints& checkpoints;
  nlohmann::json solvers;  ///< per slot {name, version}, for the checkpoints
  ProgressMonitors progress;  ///< what the progress line and the summary show
  bool can_checkpoint;     ///< every server has capability checkpoint
};

/// How the exchanges ended.
struct LoopOutcome {
  bool stopped_by_signal = false;
  bool equilibrium_reached = false;
  bool monitor_stop_reached = false;
};

/// Step 5: the exchanges. The scheme advances the participants; this records
/// each exchange, takes the snapshots and checkpoints that fall due, reports
/// progress and ends the run on a signal or a run.stop_when condition.
class ExchangeLoop {
 public:
  /// `loop`: the state the run continues from; kept up to date with the last exchange.
  ExchangeLoop(StartedRun& run, CouplingScheme& scheme, LoopState& loop)
      : run_(run),
        spec_(run.scenario.run),
        scheme_(scheme),
        loop_(loop),
        progress_(std::cerr, run.scenario.name, spec_.exchanges, run.options.progress),
        wall_start_(std::chrono::steady_clock::now() -
                    std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(loop.wall_time_s))),
        last_flush_(std::chrono::steady_clock::now()) {}

  LoopOutcome run() {
    LoopOutcome outcome;
    for (std::int64_t done = loop_.coupling.exchanges_done; done < spec_.exchanges;) {
      if (run_.stop.requested()) {
        outcome.stopped_by_signal = true;
        // Stopped at an exchange boundary with every server answering: a checkpoint, so that `run --resume` continues from here.
        if (run_.can_checkpoint && done > 0) {
          run_.stop.grant(run_.deadline);
          write_checkpoint();
        }
        break;
      }
      ExchangeResult result = scheme_.advance();
      done = result.exchange + 1;
      loop_.monitors = std::move(result.monitors);
      record(result);
      write_what_is_due(done, result.time_s);
      progress_.update(done, progress_detail(result.time_s));
      if (stop_condition_met(done, outcome)) break;
    }
    progress_.finish();
    loop_.coupling = scheme_.export_state();
    return outcome;
  }

  /// s, wall time of the run's exchanges so far (across resumed processes).
  [[nodiscard]] double elapsed() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count(); }

 private:
  void write_checkpoint() {
    loop_.wall_time_s = elapsed();
    loop_.coupling = scheme_.export_state();
    run_.checkpoints.write(run_.participants, {run_.scenario.document, run_.solvers, run_.writer.resume_point(), run_.recorder.sources(), loop_},
                           run_.deadline);
    last_flush_ = std::chrono::steady_clock::now();
  }

  void record(const ExchangeResult& r) {
    const std::map<std::string, double> fixed = {
        {"exchange", double(r.exchange + 1)},
        {"step_dem", double(r.dem_step)},
        {"step_continuum", double(r.continuum_step)},
        {"time_s", r.time_s},
        {"wall_time_s", elapsed()},
        {"interface_force_on_dem_x", r.force_on_dem[0]},
        {"interface_force_on_dem_y", r.force_on_dem[1]},
        {"interface_force_on_dem_z", r.force_on_dem[2]},
        {"interface_force_on_continuum_x", r.force_on_continuum[0]},
        {"interface_force_on_continuum_y", r.force_on_continuum[1]},
        {"interface_force_on_continuum_z", r.force_on_continuum[2]},
    };
    run_.recorder.record(fixed, loop_.monitors);
  }

  /// Snapshots and checkpoints that fall due after exchange `done` (the last
  /// exchange's are written by the run's end), and the results file's flush.
  void write_what_is_due(std::int64_t done, double time) {
    const bool snapshot_due = spec_.snapshot_every > 0 && done % spec_.snapshot_every == 0 && done < spec_.exchanges;
    if (snapshot_due) write_snapshots(run_.writer, run_.participants, time, run_.deadline);
    if (spec_.checkpoint_every > 0 && done % spec_.checkpoint_every == 0 && done < spec_.exchanges) write_checkpoint();
    // Flush at most about once a second: the file stays readable by others
    // during long runs without an HDF5 flush per exchange. Failures close the
    // writer, which writes every buffered row.
    if (snapshot_due || std::chrono::steady_clock::now() - last_flush_ > std::chrono::seconds(1)) {
      run_.writer.flush();
      last_flush_ = std::chrono::steady_clock::now();
    }
  }

  [[nodiscard]] std::string progress_detail(double time) const {
    std::ostringstream detail;
    detail.precision(3);
    detail << "t=" << time << " s";
    if (const std::string shown = shown_monitors(run_.progress, loop_.monitors); !shown.empty()) detail << " " << shown;
    if (spec_.stop_unbalanced_force_ratio)  // a run that stops on equilibrium: how far from it
      detail << " unbalanced " << largest_unbalanced_ratio(loop_.monitors) << " (stop at " << *spec_.stop_unbalanced_force_ratio << ")";
    return detail.str();
  }

  bool stop_condition_met(std::int64_t done, LoopOutcome& outcome) const {
    if (done < spec_.stop_min_exchanges) return false;
    outcome.equilibrium_reached =
        spec_.stop_unbalanced_force_ratio && every_in_equilibrium(loop_.monitors, *spec_.stop_unbalanced_force_ratio);
    outcome.monitor_stop_reached = !outcome.equilibrium_reached && spec_.stop_monitor &&
                                   monitor_reached(loop_.monitors, *spec_.stop_monitor, spec_.stop_monitor_at_least);
    return outcome.equilibrium_reached || outcome.monitor_stop_reached;
  }

  StartedRun& run_;
  const RunSpec& spec_;
  CouplingScheme& scheme_;
  LoopState& loop_;
  ProgressLine progress_;
  std::chrono::steady_clock::time_point wall_start_;
  std::chrono::steady_clock::time_point last_flush_;
};

/// The results file's `summary` attribute.
nlohmann::json run_summary(const RunSpec& spec, const CouplingState& state, const LoopOutcome& outcome, double end_time, double wall) {
  nlohmann::json summary = {{"exchanges_completed", state.exchanges_done},
                            {"dem_steps", state.dem_step},
                            {"continuum_steps", state.continuum_step},
                            {"end_time_s", end_time},
                            {"wall_time_s", wall},
                            // null when no exchange could be checked, never a misleading 0
                            {"max_relative_force_mismatch",
                             state.unchecked_balances < state.exchanges_done ? nlohmann::json(state.worst_balance) : nlohmann::json()},
                            {"force_balance_unchecked_exchanges", state.unchecked_balances},
                            {"stopped_by_signal", outcome.stopped_by_signal}};
  if (spec.stop_unbalanced_force_ratio) summary["equilibrium_reached"] = outcome.equilibrium_reached;
  if (spec.stop_monitor) summary["stop_monitor_reached"] = outcome.monitor_stop_reached;
  return summary;
}

/// The summary sentences of the final text (without the paths of the results).
std::string summary_text(const Scenario& scenario, const LoopState& loop, const ProgressMonitors& progress, const LoopOutcome& outcome,
                         bool has_dem, bool has_continuum, double end_time, double wall) {
  const CouplingState& state = loop.coupling;
  const RunSpec& spec = scenario.run;
  std::ostringstream text;
  text.precision(4);
  text << "Run '" << scenario.name << (outcome.stopped_by_signal ? "' was stopped after " : "' finished: ") << state.exchanges_done << " exchanges";
  if (has_dem) text << " (" << state.dem_step << " DEM steps";
  if (has_continuum) text << (has_dem ? ", " : " (") << state.continuum_step << " continuum steps";
  text << ", t = " << end_time << " s) in " << format_duration(wall) << ".";
  if (spec.stop_unbalanced_force_ratio)
    text << (outcome.equilibrium_reached ? " Equilibrium reached: every unbalanced_force_ratio <= "
                                         : " Equilibrium NOT reached within run.exchanges: some unbalanced_force_ratio > ")
         << *spec.stop_unbalanced_force_ratio << " (run.stop_when).";
  if (spec.stop_monitor)
    text << (outcome.monitor_stop_reached ? " Stopped when " : " Did NOT reach ") << *spec.stop_monitor << " >= " << spec.stop_monitor_at_least
         << " (run.stop_when).";
  if (const std::string shown = shown_monitors(progress, loop.monitors); !shown.empty()) text << " At the end: " << shown << ".";
  if (has_dem && has_continuum && state.unchecked_balances == 0)
    text << " The interface forces balanced at every exchange (worst relative mismatch " << state.worst_balance << ").";
  else if (has_dem && has_continuum) {
    text << " The interface force balance was NOT checked at " << state.unchecked_balances << " of " << state.exchanges_done
         << " exchanges: " << state.missing_balance_monitors << " (SPEC.md §6.3)";
    if (state.unchecked_balances < state.exchanges_done) text << "; where checked, the worst relative mismatch was " << state.worst_balance;
    text << ".";
  }
  return text.str();
}

}  // namespace

void check_scenario(const Scenario& scenario, std::ostream& log) {
  // A new folder of mode 0700 that no other user can have made first: it holds
  // the servers' logs and their key file; removed at the end, as it was made.
  const TemporaryFolder folder("dfc-check-");
  const fs::path& log_dir = folder.path();
  const protocol::RunKeyFile run_keys(log_dir);  // check's servers are as private as a run's
  zmq::context_t context(1);
  StopRequest never(nullptr);  // check installs no signal handler
  std::vector<std::unique_ptr<Participant>> participants;
  try {
    participants = start_participants(context, scenario, log_dir, never, run_keys);
    (void)progress_monitors(participants);  // a run would refuse a malformed list: so does check
    const auto [dem, continuum] = by_slot(participants);
    const ExchangeTiming timing = choose_timing(scenario, dem, continuum);
    for (auto& p : participants)
      log << "  " << p->spec().slot << ": " << p->info().solver_name << " " << p->info().solver_version << " accepted its section\n";
    log << "  exchange: " << timing.dem_steps_per_exchange << " DEM step(s) of " << timing.dt_dem << " s, "
        << timing.continuum_steps_per_exchange << " continuum step(s) of " << timing.dt_continuum << " s\n";
  } catch (...) {
    for (auto& p : participants) p->stop();
    throw;
  }
  for (auto& p : participants) p->stop();
}

int run_scenario(const Scenario& scenario, const RunOptions& options, std::ostream& log, std::ostream& error_log) {
  const fs::path out_dir = options.output_directory.empty() ? scenario.output_directory : options.output_directory;
  const fs::path log_dir = out_dir / "logs";
  const fs::path results_file = out_dir / "results.h5";
  prepare_output_folder(out_dir, log_dir, scenario, options.resume);
  const RunCheckpoints checkpoints(out_dir);
  // Read before any server starts: a run without a checkpoint is refused at once.
  const std::optional<CouplerCheckpoint> resumed = options.resume ? std::optional(checkpoints.read()) : std::nullopt;
  // Fresh keys for this run's servers in <out>/keys (SPEC.md §2.1), removed when the run ends.
  const protocol::RunKeyFile run_keys(out_dir);

  zmq::context_t context(1);
  StopRequest stop(options.stop_requested);
  std::vector<std::unique_ptr<Participant>> participants;
  const auto stop_all = [&] {
    for (auto& p : participants) p->stop();
  };
  std::unique_ptr<ResultsWriter> writer;
  // A run that ends before its summary: the reason goes into the results file
  // as attribute `attribute` and to the error log; what was written stays readable.
  const auto end_early = [&](const char* attribute, const std::string& reason, int exit_status) {
    if (writer) {
      try {
        writer->set_attribute(attribute, nlohmann::json(reason).dump());
        writer->close();
      } catch (...) {
        // keep the original reason as the message
      }
    }
    stop_all();
    error_log << "coupler: run '" << scenario.name << "' " << reason << "\n";
    if (writer) error_log << "Results up to then are in " << results_file.string() << "\n";
    return exit_status;
  };
  try {
    // Steps 1–2: start, greet, configure.
    participants = start_participants(context, scenario, log_dir, stop, run_keys);
    // Read at once: a server's malformed list fails the run before any results file exists.
    ProgressMonitors shown_progress = progress_monitors(participants);
    const auto [dem, continuum] = by_slot(participants);
    if (resumed) check_can_resume(*resumed, scenario, participants);
    const milliseconds deadline = milliseconds_from_seconds(scenario.run.deadline_s);
    const std::int64_t n_nodes = install_interface(dem, continuum, deadline);
    const ExchangeTiming timing = choose_timing(scenario, dem, continuum);  // step 4

    // Step 5 of a resumed run: every server continues from its checkpoint, the results file from where the checkpoint left it.
    if (resumed) checkpoints.restore(participants, resumed->loop, deadline);
    writer = resumed ? std::make_unique<ResultsWriter>(ResultsWriter::reopen(results_file, resumed->results))
                     : std::make_unique<ResultsWriter>(results_file, scenario.document, program_versions(participants));
    name_walls(*writer, participants, n_nodes > 0);
    RunRecorder recorder(*writer, declared_units(participants));
    if (resumed) {
      recorder.resume(resumed->recorder);
    } else {
      write_snapshots(*writer, participants, 0.0, deadline);
      writer->flush();
    }
    announce_run(log, scenario, timing, resumed, dem, continuum, n_nodes);

    // Step 5: the exchanges.
    SerialCouplingScheme scheme(dem, continuum, timing, n_nodes, scenario.coupling.force_balance_tolerance, deadline, stop);
    LoopState loop;
    if (resumed) {
      loop = resumed->loop;
      scheme.import_state(loop.coupling);
    }
    StartedRun run{scenario, options, participants, stop, deadline, *writer, recorder, checkpoints, solver_names(participants),
                   std::move(shown_progress), every_can_checkpoint(participants)};
    ExchangeLoop exchanges(run, scheme, loop);
    const LoopOutcome outcome = exchanges.run();

    // Step 6: final snapshot and summary.
    const double end_time = scheme.time();
    write_snapshots(*writer, participants, end_time, deadline);
    const double wall = exchanges.elapsed();
    writer->set_attribute("summary", run_summary(scenario.run, loop.coupling, outcome, end_time, wall).dump());
    writer->close();
    stop_all();
    log << summary_text(scenario, loop, run.progress, outcome, dem != nullptr, continuum != nullptr, end_time, wall) << "\nResults: " << results_file.string()
        << " (time series and snapshots), " << writer->xdmf_path().string() << " (open in ParaView), server logs in " << log_dir.string()
        << ".\nPlots: tools/plot_results.py " << results_file.string() << "\n";
    return outcome.stopped_by_signal ? 130 : 0;
  } catch (const ParticipantFailure& failure) {
    return end_early("failure", std::string("stopped: ") + failure.what(), 1);
  } catch (const RunInterrupted& interrupted) {
    return end_early("interrupted", interrupted.what(), 130);
  } catch (...) {
    if (writer) writer->close();
    stop_all();
    throw;
  }
}

}  // namespace dfc::coupler
