#include "dfc/coupler/run_checkpoint.hpp"

#include <sstream>

#include "dfc/common/errors.hpp"
#include "dfc/common/state_archive.hpp"
#include "dfc/common/version.hpp"
#include "dfc/protocol/checkpoint_file.hpp"
#include "dfc/protocol/error_code.hpp"

namespace dfc::coupler {

namespace {

namespace fs = std::filesystem;
constexpr const char* kCouplerFile = "coupler.checkpoint";
constexpr std::uint32_t kLayoutVersion = 2;  ///< raise when LoopState's stored members change

std::string scenario_hash(const nlohmann::json& document) { return fnv1a64_hex(document.dump()); }

protocol::CheckpointHeader coupler_header(const nlohmann::json& document, std::int64_t exchanges) {
  return {"coupler", std::string(project_version()), scenario_hash(document), exchanges};
}

std::string encode(const CouplerCheckpoint& c) {
  StateWriter out;
  out.value(kLayoutVersion);
  out.string(nlohmann::json{{"scenario", c.scenario}, {"solvers", c.solvers}, {"results", c.results}, {"recorder", c.recorder}}.dump());
  const LoopState& l = c.loop;
  out.tag("loop");
  out.value(l.coupling.exchanges_done);
  out.value(l.coupling.dem_step);
  out.value(l.coupling.continuum_step);
  out.vector(l.coupling.velocity);
  out.vector(l.coupling.continuum_displacement);
  out.vector(l.coupling.wall_displacement);
  out.value(l.coupling.worst_balance);
  out.value(l.coupling.unchecked_balances);
  out.string(l.coupling.missing_balance_monitors);
  out.value(l.wall_time_s);
  out.string(nlohmann::json(l.monitors).dump());  // numbers as shortest round-trip text: the same doubles come back
  return out.take();
}

CouplerCheckpoint decode(std::string_view bytes, const fs::path& file) {
  StateReader in(bytes, "coupler checkpoint '" + file.string() + "'");
  if (in.value<std::uint32_t>() != kLayoutVersion) in.fail("state layout " + std::to_string(kLayoutVersion));
  CouplerCheckpoint c;
  const nlohmann::json meta = nlohmann::json::parse(in.string());
  c.scenario = meta.at("scenario");
  c.solvers = meta.at("solvers");
  c.results = meta.at("results");
  c.recorder = meta.at("recorder");
  LoopState& l = c.loop;
  in.tag("loop");
  in.value(l.coupling.exchanges_done);
  in.value(l.coupling.dem_step);
  in.value(l.coupling.continuum_step);
  in.vector(l.coupling.velocity);
  in.vector(l.coupling.continuum_displacement);
  in.vector(l.coupling.wall_displacement);
  in.value(l.coupling.worst_balance);
  in.value(l.coupling.unchecked_balances);
  l.coupling.missing_balance_monitors = in.string();
  in.value(l.wall_time_s);
  l.monitors = nlohmann::json::parse(in.string()).get<std::map<std::string, nlohmann::json>>();
  in.finish();
  return c;
}

/// The scenario as a resumed run must match it. How many processes run the
/// DEM (participants.<slot>.mpi_ranks, mpi_launcher) changes no bit
/// (docs/determinism.md §3): a run may resume on another count.
nlohmann::json as_resumed(nlohmann::json document) {
  if (const auto participants = document.find("participants"); participants != document.end() && participants->is_object())
    for (auto& [slot, spec] : participants->items())
      if (spec.is_object()) {
        spec.erase("mpi_ranks");
        spec.erase("mpi_launcher");
      }
  return document;
}

/// The key paths (JSON Pointers) where two scenario documents differ, at most a few.
std::string differing_keys(const nlohmann::json& before, const nlohmann::json& now) {
  std::string keys;
  int listed = 0;
  for (const auto& change : nlohmann::json::diff(before, now)) {
    if (++listed > 5) return keys + ", ...";
    const auto path = change.find("path");
    keys += (keys.empty() ? "" : ", ") + (path != change.end() && path->is_string() ? path->get_ref<const std::string&>() : std::string("?"));
  }
  return keys;
}

}  // namespace

RunCheckpoints::RunCheckpoints(fs::path run_directory) : directory_(std::move(run_directory)) {}

fs::path RunCheckpoints::committed() const {
  std::error_code ec;
  if (fs::exists(directory_ / "checkpoint" / kCouplerFile, ec)) return directory_ / "checkpoint";
  if (fs::exists(directory_ / "checkpoint.previous" / kCouplerFile, ec)) return directory_ / "checkpoint.previous";
  throw UserError("no checkpoint in '" + directory_.string() +
                  "': the run wrote none (set run.checkpoint_every, or stop it with Ctrl-C, which writes one) or this is not a run's folder");
}

void RunCheckpoints::write(std::vector<std::unique_ptr<Participant>>& participants, const CouplerCheckpoint& state,
                           std::chrono::milliseconds deadline) const {
  const fs::path partial = directory_ / "checkpoint.partial";
  const fs::path current = directory_ / "checkpoint";
  const fs::path previous = directory_ / "checkpoint.previous";
  std::error_code ec;
  fs::remove_all(partial, ec);
  fs::create_directories(partial, ec);
  if (ec) throw UserError("cannot create the checkpoint folder '" + partial.string() + "': " + ec.message());
  for (auto& p : participants) {
    const std::string file = fs::absolute(partial / (p->spec().slot + ".checkpoint")).string();
    try {
      (void)p->client().checkpoint(file, deadline);
    } catch (const std::exception& e) {
      p->fail(e, "writing its checkpoint to " + file);
    }
  }
  try {
    protocol::write_checkpoint_file(partial / kCouplerFile, coupler_header(state.scenario, state.loop.coupling.exchanges_done), encode(state));
  } catch (const protocol::ProtocolError& e) {
    throw UserError(e.what());
  }
  // Commit: the new folder takes the place of the last; at every moment one of the two is complete.
  fs::remove_all(previous, ec);
  if (fs::exists(current, ec)) fs::rename(current, previous);
  fs::rename(partial, current);
  fs::remove_all(previous, ec);
}

CouplerCheckpoint RunCheckpoints::read() const {
  const fs::path file = committed() / kCouplerFile;
  try {
    const protocol::CheckpointFile stored = protocol::read_checkpoint_file(file);
    CouplerCheckpoint checkpoint = decode(stored.state, file);
    if (const std::string why = protocol::checkpoint_mismatch(stored.header, coupler_header(checkpoint.scenario, stored.header.step));
        !why.empty())
      throw UserError("cannot resume from '" + file.string() + "': " + why);
    return checkpoint;
  } catch (const protocol::ProtocolError& e) {
    throw UserError(std::string(e.what()) + "; resume is not possible from it");
  } catch (const StateFormatError& e) {
    throw UserError(std::string(e.what()) + "; resume is not possible from it");
  } catch (const nlohmann::json::exception& e) {
    throw UserError("coupler checkpoint '" + file.string() + "' is damaged (" + e.what() + "); resume is not possible from it");
  }
}

void RunCheckpoints::check_resumable(const CouplerCheckpoint& checkpoint, const Scenario& scenario,
                                     const std::vector<std::unique_ptr<Participant>>& participants) {
  if (scenario_hash(as_resumed(checkpoint.scenario)) != scenario_hash(as_resumed(scenario.document)))
    throw UserError("cannot resume: the scenario differs from the one the checkpointed run started with, at " +
                    differing_keys(as_resumed(checkpoint.scenario), as_resumed(scenario.document)) +
                    "; resume with the run's own scenario (its folder's scenario.json) or start a new run");
  for (const auto& p : participants) {
    const std::string& slot = p->spec().slot;
    const nlohmann::json stored = checkpoint.solvers.value(slot, nlohmann::json::object());
    const std::string name = stored.value("name", std::string("?"));
    const std::string version = stored.value("version", std::string("?"));
    if (name != p->info().solver_name || version != p->info().solver_version)
      throw UserError("cannot resume: the " + slot + " checkpoint was written by " + name + " " + version + " but the scenario now starts " +
                      p->info().solver_name + " " + p->info().solver_version +
                      "; a restart is exact only with the same build: resume with that version or start a new run");
  }
}

void RunCheckpoints::restore(std::vector<std::unique_ptr<Participant>>& participants, const LoopState& loop,
                             std::chrono::milliseconds deadline) const {
  const fs::path folder = committed();
  for (auto& p : participants) {
    const std::string& slot = p->spec().slot;
    const std::string file = fs::absolute(folder / (slot + ".checkpoint")).string();
    std::int64_t step = 0;
    try {
      step = p->client().restore(file, deadline);
    } catch (const std::exception& e) {
      p->fail(e, "restoring its checkpoint " + file);
    }
    const std::int64_t expected = slot == "dem" ? loop.coupling.dem_step : loop.coupling.continuum_step;
    if (step != expected)
      throw UserError("cannot resume: " + p->label() + " restored step " + std::to_string(step) + " from " + file + " but the coupler's checkpoint is at step " +
                      std::to_string(expected) + "; the checkpoint folder mixes two checkpoints: start a new run");
  }
}

}  // namespace dfc::coupler
