#include "dfc/coupler/coupled_run.hpp"

#include <unistd.h>

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
#include "dfc/common/version.hpp"
#include "dfc/coupler/progress_line.hpp"
#include "dfc/coupler/results_writer.hpp"
#include "dfc/coupler/run_checkpoint.hpp"
#include "dfc/protocol/message.hpp"
#include "dfc/protocol/monitor_units.hpp"

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

/// The [x, y, z] monitor `name`, or nullopt when the server did not send it.
/// Entries that are not numbers read as NaN, so the balance check catches them.
std::optional<std::array<double, 3>> vector_monitor(const nlohmann::json& monitors, const char* name) {
  const auto it = monitors.find(name);
  if (it == monitors.end() || !it->is_array() || it->size() != 3) return std::nullopt;
  const auto component = [&](std::size_t i) { return (*it)[i].is_number() ? (*it)[i].get<double>() : kNaN; };
  return std::array<double, 3>{component(0), component(1), component(2)};
}

bool all_finite(const std::array<double, 3>& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

/// Throws naming the first node row of interface array `name` that holds a NaN
/// or an infinity; the caller blames the server that sent it.
void require_finite_rows(const std::vector<double>& values, const char* name) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw SolverError("it sent a non-finite interface " + std::string(name) + " (" + std::to_string(values[i]) + " in node row " +
                        std::to_string(i / 3) + ")");
}

std::optional<double> info_number(const nlohmann::json& info, const char* key) {
  const auto it = info.find(key);
  if (it == info.end() || !it->is_number()) return std::nullopt;
  return it->get<double>();
}

std::string format_vector(const std::array<double, 3>& v) {
  std::ostringstream out;
  out.precision(6);
  out << "[" << v[0] << ", " << v[1] << ", " << v[2] << "]";
  return out.str();
}

/// Time steps of the run (SPEC.md §5.3): exchange duration T = k·dt_dem = m·dt_continuum.
struct Timing {
  std::int64_t dem_steps_per_exchange = 0;
  std::int64_t continuum_steps_per_exchange = 0;
  double dt_dem = 0.0;
  double dt_continuum = 0.0;
  [[nodiscard]] double exchange_duration() const {
    return dem_steps_per_exchange > 0 ? double(dem_steps_per_exchange) * dt_dem : double(continuum_steps_per_exchange) * dt_continuum;
  }
};

Timing choose_timing(const Scenario& scenario, Participant* dem, Participant* continuum) {
  Timing timing;
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

/// Bytes per particle in a snapshot (SPEC.md §6.4): position and velocity f64 [3], radius f64, id i64.
constexpr double kSnapshotBytesPerParticle = (3 + 3 + 1 + 1) * 8.0;

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
/// than the machine has. Otherwise a 1e7-particle bed passed `check` and died
/// with a bare std::bad_alloc at the first snapshot. Only particle counts are
/// estimated (the DEM's `particle_count` monitor): continua stay far smaller.
void check_snapshot_memory(Participant& p, milliseconds deadline) {
  if (!p.has(protocol::capability::snapshot)) return;
  nlohmann::json monitors;
  try {
    monitors = p.client().query(deadline);
  } catch (const std::exception& e) {
    p.fail(e, "reporting its configured state (query)");
  }
  const double particles = scalar_monitor(monitors, "particle_count");
  if (!std::isfinite(particles)) return;
  const std::string key = p.spec().key_path() + ".config" + (p.spec().config.contains("particles") ? ".particles" : "");
  const auto gib = [](double bytes) {
    std::ostringstream text;
    text.precision(3);
    text << bytes / double(1ULL << 30) << " GiB";
    return text.str();
  };
  const double largest_array = particles * 3 * 8;
  const double array_limit = double(protocol::Limits{}.max_array_bytes);
  if (largest_array > array_limit)
    throw ConfigError(key, "the model has " + std::to_string(static_cast<long long>(particles)) + " particles; their positions in a snapshot take " +
                               gib(largest_array) + ", over the protocol's " + gib(array_limit) +
                               " per array (SPEC.md §8): use fewer particles or larger ones");
  // While a snapshot is received the coupler holds it twice (the frames and
  // the decoded arrays) and the HDF5 writer a third time.
  const double needed = 3 * particles * kSnapshotBytesPerParticle;
  if (const auto available = available_memory_bytes(); available && needed > *available)
    throw ConfigError(key, "the model has " + std::to_string(static_cast<long long>(particles)) + " particles; taking a snapshot of them needs about " +
                               gib(needed) + " in the coupler but this machine has " + gib(*available) +
                               " available: use fewer particles or larger ones, or a machine with more memory");
}

/// Starts and greets the participants; configures them; throws on the first problem.
std::vector<std::unique_ptr<Participant>> start_participants(zmq::context_t& context, const Scenario& scenario, const fs::path& log_dir,
                                                            StopRequest& stop) {
  std::vector<std::unique_ptr<Participant>> participants;
  for (const auto& spec : scenario.participants) {
    participants.push_back(
        std::make_unique<Participant>(context, spec, log_dir, milliseconds_from_seconds(scenario.run.startup_timeout_s), stop));
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

/// The run's time series: the coupler's own columns and every monitor of
/// every slot, each labelled with the unit its source declares (SPEC.md §6.3).
/// A monitor that is a number is a 1-D column; an [x, y, z] one an [N, 3] column.
class RunRecorder {
 public:
  /// `declared_units`: per slot, configure's info.monitor_units (null for a
  /// server that declares none, e.g. one speaking protocol 1.1).
  RunRecorder(ResultsWriter& writer, std::map<std::string, nlohmann::json> declared_units)
      : writer_(writer), declared_units_(std::move(declared_units)) {}

  void record(const std::map<std::string, double>& fixed, const std::map<std::string, nlohmann::json>& monitors_by_slot) {
    if (columns_.empty()) declare(fixed, monitors_by_slot);
    std::vector<double> row;
    for (const Source& column : columns_) {
      if (column.slot.empty()) {
        const auto it = fixed.find(column.key);
        row.push_back(it == fixed.end() ? kNaN : it->second);
        continue;
      }
      // A monitor missing from this reply, or of another shape than at the first row, is recorded as NaN.
      const auto slot = monitors_by_slot.find(column.slot);
      const nlohmann::json* value = slot == monitors_by_slot.end() || !slot->second.contains(column.key) ? nullptr : &slot->second[column.key];
      const bool fits = value != nullptr && protocol::monitor_width(*value) == column.width;
      if (column.width == 1) row.push_back(fits ? value->get<double>() : kNaN);
      else
        for (std::size_t i = 0; i < column.width; ++i) row.push_back(fits ? (*value)[i].get<double>() : kNaN);
    }
    writer_.append(row);
  }

  /// Where each column comes from, for a checkpoint (empty before the first row).
  [[nodiscard]] nlohmann::json sources() const {
    nlohmann::json out = nlohmann::json::array();
    for (const Source& c : columns_) out.push_back({{"slot", c.slot}, {"key", c.key}, {"width", c.width}});
    return out;
  }
  /// A resumed run: the columns the results file already declares.
  void resume(const nlohmann::json& sources) {
    for (const auto& c : sources) columns_.push_back({c.at("slot").get<std::string>(), c.at("key").get<std::string>(), c.at("width").get<std::size_t>()});
  }

 private:
  /// Where a column's values come from: `fixed[key]` when `slot` is empty, else the slot's monitor `key`.
  struct Source {
    std::string slot;
    std::string key;
    std::size_t width = 1;
  };

  /// For a server that declares no units: a guess from the monitor's name
  /// suffix (SPEC.md §6.3 naming), stored marked as a guess.
  static std::string unit_guessed_from_name(const std::string& name) {
    const auto ends = [&](std::string_view suffix) { return name.ends_with(suffix); };
    if (ends("_n_s")) return protocol::unit::newton_second;
    if (ends("_s")) return protocol::unit::second;
    if (ends("_m")) return protocol::unit::metre;
    if (ends("_n")) return protocol::unit::newton;
    if (ends("_nm")) return protocol::unit::newton_metre;
    if (ends("_pa")) return protocol::unit::pascal;
    if (ends("_w")) return protocol::unit::watt;
    if (ends("_j")) return protocol::unit::joule;
    return protocol::unit::dimensionless;
  }

  /// The unit of `slot`'s monitor `name` as its server declared it, else the guess.
  SeriesColumn monitor_column(const std::string& slot, const std::string& name, std::size_t width) const {
    const auto declared = declared_units_.find(slot);
    if (declared != declared_units_.end() && declared->second.is_object()) {
      const auto unit = declared->second.find(name);
      if (unit != declared->second.end() && unit->is_string()) return {slot + "_" + name, unit->get<std::string>(), width};
    }
    return {slot + "_" + name, unit_guessed_from_name(name), width, true};
  }

  void declare(const std::map<std::string, double>& fixed, const std::map<std::string, nlohmann::json>& monitors_by_slot) {
    // The coupler's own columns (coupled_run's `fixed`): their units are its own declaration.
    static const std::map<std::string, std::string> coupler_units = {
        {"exchange", protocol::unit::dimensionless},          {"step_dem", protocol::unit::dimensionless},
        {"step_continuum", protocol::unit::dimensionless},    {"time_s", protocol::unit::second},
        {"wall_time_s", protocol::unit::second},              {"interface_force_on_dem_x", protocol::unit::newton},
        {"interface_force_on_dem_y", protocol::unit::newton}, {"interface_force_on_dem_z", protocol::unit::newton},
        {"interface_force_on_continuum_x", protocol::unit::newton},
        {"interface_force_on_continuum_y", protocol::unit::newton},
        {"interface_force_on_continuum_z", protocol::unit::newton}};
    std::map<std::string, std::pair<Source, SeriesColumn>> by_name;  // columns in name order, as before units were declared
    for (const auto& [name, value] : fixed) {
      const auto unit = coupler_units.find(name);
      SeriesColumn column = unit != coupler_units.end() ? SeriesColumn{name, unit->second} : SeriesColumn{name, unit_guessed_from_name(name), 1, true};
      by_name.emplace(name, std::pair{Source{"", name, 1}, std::move(column)});
    }
    for (const auto& [slot, monitors] : monitors_by_slot)
      for (const auto& [name, value] : monitors.items())
        if (const std::size_t width = protocol::monitor_width(value); width > 0)
          by_name.emplace(slot + "_" + name, std::pair{Source{slot, name, width}, monitor_column(slot, name, width)});
    std::vector<SeriesColumn> columns;
    for (auto& [name, entry] : by_name) {
      columns_.push_back(std::move(entry.first));
      columns.push_back(std::move(entry.second));
    }
    writer_.declare_series(columns);
  }

  ResultsWriter& writer_;
  std::map<std::string, nlohmann::json> declared_units_;
  std::vector<Source> columns_;
};

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

}  // namespace

void check_scenario(const Scenario& scenario, std::ostream& log) {
  const fs::path log_dir = fs::temp_directory_path() / ("dfc-check-" + std::to_string(::getpid()));
  fs::create_directories(log_dir);
  zmq::context_t context(1);
  StopRequest never(nullptr);  // check installs no signal handler
  std::vector<std::unique_ptr<Participant>> participants;
  try {
    participants = start_participants(context, scenario, log_dir, never);
    Participant* dem = nullptr;
    Participant* continuum = nullptr;
    for (auto& p : participants) (p->spec().slot == "dem" ? dem : continuum) = p.get();
    const Timing timing = choose_timing(scenario, dem, continuum);
    for (auto& p : participants)
      log << "  " << p->spec().slot << ": " << p->info().solver_name << " " << p->info().solver_version << " accepted its section\n";
    log << "  exchange: " << timing.dem_steps_per_exchange << " DEM step(s) of " << timing.dt_dem << " s, "
        << timing.continuum_steps_per_exchange << " continuum step(s) of " << timing.dt_continuum << " s\n";
  } catch (...) {
    for (auto& p : participants) p->stop();
    fs::remove_all(log_dir);
    throw;
  }
  for (auto& p : participants) p->stop();
  fs::remove_all(log_dir);
}

int run_scenario(const Scenario& scenario, const RunOptions& options, std::ostream& log, std::ostream& error_log) {
  const fs::path out_dir = options.output_directory.empty() ? scenario.output_directory : options.output_directory;
  const fs::path log_dir = out_dir / "logs";
  std::error_code ec;
  fs::create_directories(log_dir, ec);
  if (ec) throw UserError("cannot create the output folder '" + log_dir.string() + "': " + ec.message() + "; choose another with --out");
  if (!options.resume) {  // a resumed run reads its scenario from this copy
    std::ofstream copy(out_dir / "scenario.json");
    copy << readable_json(scenario.document) << "\n";
  }
  const RunCheckpoints checkpoints(out_dir);
  // Read before any server starts: a run without a checkpoint is refused at once.
  const std::optional<CouplerCheckpoint> resumed = options.resume ? std::optional(checkpoints.read()) : std::nullopt;

  zmq::context_t context(1);
  StopRequest stop(options.stop_requested);
  std::vector<std::unique_ptr<Participant>> participants;
  const auto stop_all = [&] {
    for (auto& p : participants) p->stop();
  };
  std::unique_ptr<ResultsWriter> writer;
  int status = 0;
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
    if (writer) error_log << "Results up to then are in " << (out_dir / "results.h5").string() << "\n";
    return exit_status;
  };
  try {
    // Steps 1–2: start, greet, configure.
    participants = start_participants(context, scenario, log_dir, stop);
    Participant* dem = nullptr;
    Participant* continuum = nullptr;
    for (auto& p : participants) (p->spec().slot == "dem" ? dem : continuum) = p.get();
    if (resumed) {
      RunCheckpoints::check_resumable(*resumed, scenario, participants);
      for (auto& p : participants)
        if (!p->has(protocol::capability::checkpoint))
          throw UserError("cannot resume: the " + p->spec().slot + " server '" + p->spec().program + "' lacks capability 'checkpoint'");
    }
    const bool coupled = dem != nullptr && continuum != nullptr;
    const milliseconds deadline = milliseconds_from_seconds(scenario.run.deadline_s);

    // Step 3: the interface mesh goes from the continuum to the DEM (docs/theory/coupling.md §2).
    protocol::InterfaceMesh interface;
    if (coupled) {
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
    }
    const std::int64_t n_nodes = interface.node_count();

    // Step 4: time steps.
    const Timing timing = choose_timing(scenario, dem, continuum);

    nlohmann::json versions = {{"coupler", {{"name", "coupler"}, {"version", std::string(project_version())}}},
                               {"protocol", protocol::version_string()}};
    for (auto& p : participants)
      versions[p->spec().slot] = {{"name", p->info().solver_name},
                                  {"version", p->info().solver_version},
                                  {"protocol", p->info().protocol_version},
                                  {"configured", p->configured_info()}};
    // Step 5 of a resumed run: every server continues from its checkpoint, the results file from where the checkpoint left it.
    if (resumed) {
      checkpoints.restore(participants, resumed->loop, deadline);
      writer = std::make_unique<ResultsWriter>(ResultsWriter::reopen(out_dir / "results.h5", resumed->results));
    } else {
      writer = std::make_unique<ResultsWriter>(out_dir / "results.h5", scenario.document, versions);
    }
    std::map<std::string, nlohmann::json> declared_units;
    for (auto& p : participants) declared_units[p->spec().slot] = p->configured_info().value(protocol::monitor_units_key, nlohmann::json());
    RunRecorder recorder(*writer, std::move(declared_units));
    if (resumed) {
      recorder.resume(resumed->recorder);
    } else {
      write_snapshots(*writer, participants, 0.0, deadline);
      writer->flush();
    }
    nlohmann::json solvers = nlohmann::json::object();
    for (auto& p : participants) solvers[p->spec().slot] = {{"name", p->info().solver_name}, {"version", p->info().solver_version}};
    // Checkpoints need every server's capability; without run.checkpoint_every a stop by signal still writes one where they have it.
    bool can_checkpoint = true;
    for (auto& p : participants) can_checkpoint = can_checkpoint && p->has(protocol::capability::checkpoint);

    log << (resumed ? "Resuming run '" : "Run '") << scenario.name << "'";
    if (resumed) log << " after exchange " << resumed->loop.exchanges_done;
    log << ": " << scenario.run.exchanges << " exchanges";
    if (dem) log << ", " << timing.dem_steps_per_exchange << " DEM step(s) of " << timing.dt_dem << " s";
    if (continuum) log << ", " << timing.continuum_steps_per_exchange << " continuum step(s) of " << timing.dt_continuum << " s";
    if (coupled) log << ", " << n_nodes << " interface nodes";
    log << " each." << std::endl;  // flushed: a supervisor reading the log sees the run start

    // Step 5: the exchanges.
    // Interface kinematics. The continuum returns its gridpoint velocity and
    // displacement at the end of each advance; the DEM moves its wall vertices
    // at the velocity it is sent for the whole exchange. Sending the bare
    // end-of-advance velocity would let the wall drift from the gridpoints
    // whenever k or m > 1 (the continuum's velocity varies inside its advance),
    // so the coupler tracks where it has moved the wall (x += v·dt, step by
    // step, as the DEM does) and adds the correction that brings the wall onto
    // the continuum's displacement: v_sent = v + (u_continuum − u_wall) / T.
    // Everything the loop carries between exchanges is in `loop` (run_checkpoint.hpp), so a checkpoint holds it all.
    LoopState loop;
    if (resumed) {
      loop = resumed->loop;
    } else {
      loop.velocity.assign(std::size_t(n_nodes) * 3, 0.0);
      loop.continuum_displacement.assign(loop.velocity.size(), 0.0);
      loop.wall_displacement.assign(loop.velocity.size(), 0.0);
    }
    std::vector<double>& velocity = loop.velocity;
    std::vector<double>& continuum_displacement = loop.continuum_displacement;
    std::vector<double>& wall_displacement = loop.wall_displacement;
    std::int64_t& dem_step = loop.dem_step;
    std::int64_t& continuum_step = loop.continuum_step;
    double& worst_balance = loop.worst_balance;
    // Exchanges at which a side sent no interface force monitor (SPEC.md §6.3
    // names them, but a server may omit them): the balance was not checked there.
    std::int64_t& unchecked_balances = loop.unchecked_balances;
    std::string& missing_balance_monitors = loop.missing_balance_monitors;
    double& peak_pile_force = loop.peak_pile_force;
    std::int64_t& done = loop.exchanges_done;
    std::map<std::string, nlohmann::json>& monitors = loop.monitors;
    ProgressLine progress(std::cerr, scenario.name, scenario.run.exchanges, options.progress);
    const auto wall_start = std::chrono::steady_clock::now() - std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                                  std::chrono::duration<double>(loop.wall_time_s));
    auto last_flush = std::chrono::steady_clock::now();
    bool equilibrium_reached = false;
    bool monitor_stop_reached = false;
    const auto write_checkpoint = [&] {
      loop.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
      checkpoints.write(participants, {scenario.document, solvers, writer->resume_point(), recorder.sources(), loop}, deadline);
      last_flush = std::chrono::steady_clock::now();
    };
    for (std::int64_t exchange = loop.exchanges_done; exchange < scenario.run.exchanges; ++exchange) {
      if (options.stop_requested != nullptr && options.stop_requested->load()) {
        status = 130;
        // Stopped at an exchange boundary with every server answering: a checkpoint, so that `run --resume` continues from here.
        if (can_checkpoint && done > 0) {
          stop.grant(deadline);
          write_checkpoint();
        }
        break;
      }
      std::vector<protocol::Array> to_continuum;
      if (dem != nullptr) {
        std::vector<protocol::Array> inputs;
        if (coupled) {
          const double exchange_time = timing.exchange_duration();
          std::vector<double> sent(velocity.size());
          for (std::size_t i = 0; i < sent.size(); ++i) {
            stop.check("the coupler's update of the wall positions");  // k can be 1e9 steps per node
            sent[i] = velocity[i] + (continuum_displacement[i] - wall_displacement[i]) / exchange_time;
            for (std::int64_t s = 0; s < timing.dem_steps_per_exchange; ++s) wall_displacement[i] += sent[i] * timing.dt_dem;
          }
          inputs.push_back(protocol::Array::from_f64(protocol::field::velocity, {n_nodes, 3}, sent));
        }
        protocol::Message reply;
        try {
          reply = dem->client().advance(dem_step, timing.dem_steps_per_exchange, timing.dt_dem, std::move(inputs), deadline);
          if (coupled) {
            const std::vector<double> force = protocol::require_f64(reply.arrays, protocol::field::force, n_nodes, 3);
            require_finite_rows(force, "force");
            to_continuum.push_back(protocol::Array::from_f64(protocol::field::force, {n_nodes, 3}, force));
            // A driven continuum also lends its interface mass (SPEC.md §6.1).
            if (protocol::find_array(reply.arrays, protocol::field::mass) != nullptr)
              to_continuum.push_back(protocol::Array::from_f64(protocol::field::mass, {n_nodes},
                                                               protocol::require_f64(reply.arrays, protocol::field::mass, n_nodes, 0)));
          }
        } catch (const std::exception& e) {
          dem->fail(e, "advancing from step " + std::to_string(dem_step));
        }
        dem_step = *reply.step;
        monitors["dem"] = reply.body.value("monitors", nlohmann::json::object());
      }
      if (continuum != nullptr) {
        protocol::Message reply;
        try {
          reply = continuum->client().advance(continuum_step, timing.continuum_steps_per_exchange, timing.dt_continuum,
                                              std::move(to_continuum), deadline);
          if (coupled) {
            velocity = protocol::require_f64(reply.arrays, protocol::field::velocity, n_nodes, 3);
            continuum_displacement = protocol::require_f64(reply.arrays, protocol::field::displacement, n_nodes, 3);
            // Caught here, a NaN is blamed on the continuum that produced it, not on the DEM it would break next.
            require_finite_rows(velocity, "velocity");
            require_finite_rows(continuum_displacement, "displacement");
          }
        } catch (const std::exception& e) {
          continuum->fail(e, "advancing from step " + std::to_string(continuum_step));
        }
        continuum_step = *reply.step;
        monitors["continuum"] = reply.body.value("monitors", nlohmann::json::object());
      }

      // The interface forces must be equal and opposite (docs/theory/coupling.md §4): the reaction
      // the DEM computed on its particles against what the continuum applied.
      std::array<double, 3> on_dem{kNaN, kNaN, kNaN};
      std::array<double, 3> on_continuum{kNaN, kNaN, kNaN};
      if (coupled) {
        const auto reaction = vector_monitor(monitors["dem"], "interface_force_reaction");
        const auto received = vector_monitor(monitors["continuum"], "interface_force_received");
        if (reaction) on_dem = *reaction;
        if (received) on_continuum = *received;
        if (!reaction || !received) {
          ++unchecked_balances;
          if (missing_balance_monitors.empty())
            missing_balance_monitors = !reaction ? "the dem server sent no interface_force_reaction" : "the continuum server sent no interface_force_received";
        } else {
          double mismatch = 0.0;
          double scale = 0.0;
          for (std::size_t i = 0; i < 3; ++i) {
            mismatch = std::max(mismatch, std::abs(on_dem[i] + on_continuum[i]));
            scale = std::max({scale, std::abs(on_dem[i]), std::abs(on_continuum[i])});
          }
          // std::max drops NaN, so non-finite forces are tested for on their own.
          const double relative = !all_finite(on_dem) || !all_finite(on_continuum) ? kNaN : scale > 0 ? mismatch / scale : mismatch;
          if (!std::isfinite(relative) || relative > scenario.coupling.force_balance_tolerance) {
            std::ostringstream message;
            message << "interface force balance broken at exchange " << exchange << " (DEM step " << dem_step << "): force on the DEM side "
                    << format_vector(on_dem) << " N (interface_force_reaction) and on the continuum " << format_vector(on_continuum)
                    << " N (interface_force_received) are not equal and opposite; relative mismatch " << relative << " > tolerance "
                    << scenario.coupling.force_balance_tolerance << " (coupling.force_balance_tolerance)";
            throw ParticipantFailure(message.str());
          }
          worst_balance = std::max(worst_balance, relative);
        }
      }

      const double time = dem != nullptr ? double(dem_step) * timing.dt_dem : double(continuum_step) * timing.dt_continuum;
      const double pile_force = scalar_monitor(monitors["dem"], "pile_force_n");
      if (std::isfinite(pile_force) && !(pile_force <= peak_pile_force)) peak_pile_force = pile_force;
      const std::map<std::string, double> fixed = {
          {"exchange", double(exchange + 1)},
          {"step_dem", double(dem_step)},
          {"step_continuum", double(continuum_step)},
          {"time_s", time},
          {"wall_time_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count()},
          {"interface_force_on_dem_x", on_dem[0]},
          {"interface_force_on_dem_y", on_dem[1]},
          {"interface_force_on_dem_z", on_dem[2]},
          {"interface_force_on_continuum_x", on_continuum[0]},
          {"interface_force_on_continuum_y", on_continuum[1]},
          {"interface_force_on_continuum_z", on_continuum[2]},
      };
      recorder.record(fixed, monitors);
      ++done;  // loop.exchanges_done
      const bool snapshot_due = scenario.run.snapshot_every > 0 && (exchange + 1) % scenario.run.snapshot_every == 0 &&
                                exchange + 1 < scenario.run.exchanges;
      if (snapshot_due) write_snapshots(*writer, participants, time, deadline);
      if (scenario.run.checkpoint_every > 0 && (exchange + 1) % scenario.run.checkpoint_every == 0 && exchange + 1 < scenario.run.exchanges)
        write_checkpoint();
      // Flush at most about once a second: the file stays readable by others
      // during long runs without an HDF5 flush per exchange. Failures close the
      // writer, which writes every buffered row.
      if (snapshot_due || std::chrono::steady_clock::now() - last_flush > std::chrono::seconds(1)) {
        writer->flush();
        last_flush = std::chrono::steady_clock::now();
      }

      std::ostringstream detail;
      detail.precision(3);
      detail << "t=" << time << " s";
      if (std::isfinite(pile_force))
        detail << " pile " << 1e3 * scalar_monitor(monitors["dem"], "pile_displacement_m") << " mm, " << pile_force << " N";
      if (scenario.run.stop_unbalanced_force_ratio)  // a run that stops on equilibrium: how far from it
        detail << " unbalanced " << largest_unbalanced_ratio(monitors) << " (stop at " << *scenario.run.stop_unbalanced_force_ratio << ")";
      progress.update(done, detail.str());
      if (scenario.run.stop_unbalanced_force_ratio && done >= scenario.run.stop_min_exchanges &&
          every_in_equilibrium(monitors, *scenario.run.stop_unbalanced_force_ratio)) {
        equilibrium_reached = true;
        break;
      }
      if (scenario.run.stop_monitor && done >= scenario.run.stop_min_exchanges &&
          monitor_reached(monitors, *scenario.run.stop_monitor, scenario.run.stop_monitor_at_least)) {
        monitor_stop_reached = true;
        break;
      }
    }
    progress.finish();
    // Step 6: final snapshot and summary.
    const double end_time = dem != nullptr ? double(dem_step) * timing.dt_dem : double(continuum_step) * timing.dt_continuum;
    write_snapshots(*writer, participants, end_time, deadline);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    nlohmann::json summary = {{"exchanges_completed", done},
                              {"dem_steps", dem_step},
                              {"continuum_steps", continuum_step},
                              {"end_time_s", end_time},
                              {"wall_time_s", wall},
                              // null when no exchange could be checked, never a misleading 0
                              {"max_relative_force_mismatch", unchecked_balances < done ? nlohmann::json(worst_balance) : nlohmann::json()},
                              {"force_balance_unchecked_exchanges", unchecked_balances},
                              {"stopped_by_signal", status == 130}};
    if (scenario.run.stop_unbalanced_force_ratio) summary["equilibrium_reached"] = equilibrium_reached;
    if (scenario.run.stop_monitor) summary["stop_monitor_reached"] = monitor_stop_reached;
    writer->set_attribute("summary", summary.dump());
    writer->close();
    stop_all();

    std::ostringstream text;
    text.precision(4);
    text << (status == 130 ? "Run '" + scenario.name + "' was stopped after " : "Run '" + scenario.name + "' finished: ") << done
         << " exchanges";
    if (dem) text << " (" << dem_step << " DEM steps";
    if (continuum) text << (dem ? ", " : " (") << continuum_step << " continuum steps";
    text << ", t = " << end_time << " s) in " << format_duration(wall) << ".";
    if (scenario.run.stop_unbalanced_force_ratio)
      text << (equilibrium_reached ? " Equilibrium reached: every unbalanced_force_ratio <= " : " Equilibrium NOT reached within run.exchanges: some unbalanced_force_ratio > ")
           << *scenario.run.stop_unbalanced_force_ratio << " (run.stop_when).";
    if (scenario.run.stop_monitor)
      text << (monitor_stop_reached ? " Stopped when " : " Did NOT reach ") << *scenario.run.stop_monitor << " >= "
           << scenario.run.stop_monitor_at_least << " (run.stop_when).";
    if (std::isfinite(peak_pile_force))
      text << " Pile penetration " << 1e3 * scalar_monitor(monitors["dem"], "pile_displacement_m") << " mm, final pile force "
           << scalar_monitor(monitors["dem"], "pile_force_n") << " N (peak " << peak_pile_force << " N).";
    if (coupled && unchecked_balances == 0)
      text << " The interface forces balanced at every exchange (worst relative mismatch " << worst_balance << ").";
    else if (coupled) {
      text << " The interface force balance was NOT checked at " << unchecked_balances << " of " << done << " exchanges: "
           << missing_balance_monitors << " (SPEC.md §6.3)";
      if (unchecked_balances < done) text << "; where checked, the worst relative mismatch was " << worst_balance;
      text << ".";
    }
    text << "\nResults: " << (out_dir / "results.h5").string() << " (time series and snapshots), " << writer->xdmf_path().string()
         << " (open in ParaView), server logs in " << log_dir.string() << ".\nPlots: tools/plot_results.py " << (out_dir / "results.h5").string()
         << "\n";
    log << text.str();
    return status;
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
