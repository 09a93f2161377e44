#include "fixture_backend.hpp"

#include <array>
#include <chrono>
#include <algorithm>
#include <cstdlib>
#include <future>
#include <limits>
#include <stdexcept>
#include <thread>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/unstable_step_error.hpp"
#include "dfc/common/version.hpp"
#include "dfc/common/work_progress.hpp"
#include "dfc/protocol/monitor_units.hpp"
#include "dfc/protocol/progress_monitors.hpp"
#include "square_grid_mesh.hpp"

namespace dfc::protocol::testing {

namespace {
constexpr double kNodeMass = 1.0;  // kg, before any lumped mass from the other side
constexpr double kDtMax = 1e-2;    // s, the stability limit the fixture announces and enforces (SPEC.md §5.2)
constexpr auto kWorkSlice = std::chrono::milliseconds(100);  // a slow advance's "step": one progress bump
}

std::optional<Breakage> breakage_from_name(std::string_view name) noexcept {
  if (name == "throw") return Breakage::throw_in_advance;
  if (name == "shape") return Breakage::wrong_output_shape;
  if (name == "crash") return Breakage::crash_in_advance;
  if (name == "hang") return Breakage::hang_in_advance;
  if (name == "no-force-monitor") return Breakage::no_force_monitor;
  if (name == "nan-velocity") return Breakage::nan_velocity;
  if (name == "huge-particle-count") return Breakage::huge_particle_count;
  if (name == "unsent-progress-monitor") return Breakage::unsent_progress_monitor;
  if (name == "malformed-progress-monitors") return Breakage::malformed_progress_monitors;
  if (name == "no-heartbeat") return Breakage::no_heartbeat;
  if (name == "no-authentication") return Breakage::no_authentication;
  if (name == "accept-surplus-input") return Breakage::accepts_surplus_input;
  if (name == "deadlock-advance") return Breakage::deadlock_in_advance;
  if (name == "no-progress") return Breakage::no_progress;
  return std::nullopt;
}

SolverIdentity FixtureBackend::identity() const {
  return {"conformance_fixture_server", std::string(project_version()), "continuum", {capability::provides_interface, capability::snapshot}};
}

nlohmann::json FixtureBackend::configure(const nlohmann::json& section) {
  ConfigReader config(section, "");
  const std::int64_t side = config.integer("side", 2, 2);
  advance_seconds_ = config.number("advance_s", 0.0, Bounds{0.0, 60.0});
  interface_ = config.boolean("interface", true);
  (void)config.vec3("gravity_m_s2", {0.0, 0.0, 0.0});  // added by the coupler to every section (SPEC.md §4.2); unused here
  config.finish();
  mesh_ = square_grid_mesh(side);
  velocity_.assign(mesh_.coordinates.size(), 0.0);
  displacement_.assign(mesh_.coordinates.size(), 0.0);
  if (breakage_ == Breakage::huge_particle_count) monitors_ = {{"particle_count", 2e10}};
  nlohmann::json units = shared_monitor_units();
  units["particle_count"] = unit::dimensionless;  // sent by the huge_particle_count breakage only
  // What the coupler shows while a run goes (SPEC.md §4.2, 1.5): the interface's kinetic energy, in mJ.
  std::vector<ProgressMonitor> progress = {{"kinetic_energy_j", "energy", 1e3, "mJ"}};
  if (breakage_ == Breakage::unsent_progress_monitor) {
    progress.push_back({"fixture_never_sent", "never", 1.0, "1"});
    units["fixture_never_sent"] = unit::dimensionless;
  }
  const nlohmann::json listed = breakage_ == Breakage::malformed_progress_monitors ? nlohmann::json("kinetic_energy_j") : to_json(progress);
  nlohmann::json info = {{"dt_suggested", 1e-3}, {"dt_max", kDtMax}};
  if (declared_minor_ >= 2) info[monitor_units_key] = units;        // SPEC.md §1, 1.2
  if (declared_minor_ >= 5) info[progress_monitors_key] = listed;  // SPEC.md §1, 1.5
  if (!interface_) info["capabilities"] = {capability::snapshot};  // uncoupled: a run of this server alone (SPEC.md §4.2)
  return info;
}

AdvanceResult FixtureBackend::advance(const AdvanceRequest& request) {
  switch (breakage_) {
    case Breakage::throw_in_advance: throw std::runtime_error("deliberately broken fixture: advance throws");
    case Breakage::crash_in_advance: std::abort();
    case Breakage::hang_in_advance: std::this_thread::sleep_for(std::chrono::hours(1)); break;
    case Breakage::deadlock_in_advance: {
      // Waits for a promise nobody keeps: no work, no progress, while the heartbeat thread answers.
      std::promise<void> never_kept;
      never_kept.get_future().wait();
      break;
    }
    case Breakage::none:
    case Breakage::wrong_output_shape:
    case Breakage::no_force_monitor:
    case Breakage::nan_velocity:
    case Breakage::huge_particle_count:
    case Breakage::unsent_progress_monitor:
    case Breakage::malformed_progress_monitors:
    case Breakage::no_heartbeat:
    case Breakage::no_authentication:
    case Breakage::accepts_surplus_input:
    case Breakage::no_progress: break;
  }
  if (request.dt > kDtMax) throw UnstableStepError("dt exceeds the fixture's stability limit", kDtMax);  // before anything changes
  // A slow solver: the main thread is busy, the heartbeat thread answers and,
  // as a real solver's steps do, the work counter moves every 0.1 s (SPEC.md §9.1).
  const std::chrono::steady_clock::time_point slow_until =
      std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(advance_seconds_));
  while (std::chrono::steady_clock::now() < slow_until) {
    std::this_thread::sleep_until(std::min(slow_until, std::chrono::steady_clock::now() + kWorkSlice));
    work_progress::advance();
  }
  const std::int64_t n = mesh_.node_count();
  // A 1.0 server ignores input arrays it does not take (SPEC.md §1, 1.1).
  if (declared_minor_ >= 1 && breakage_ != Breakage::accepts_surplus_input) {
    if (interface_) require_only(request.inputs, {field::force, field::mass}, "conformance_fixture_server");
    else require_only(request.inputs, {}, "conformance_fixture_server");
  }
  const std::vector<double> force =
      interface_ ? require_f64(request.inputs, field::force, n, 3) : std::vector<double>(static_cast<std::size_t>(3 * n), 0.0);
  std::vector<double> lumped(static_cast<std::size_t>(n), 0.0);
  if (find_array(request.inputs, field::mass) != nullptr) lumped = require_f64(request.inputs, field::mass, n, 0);
  // Explicit Euler per node; good enough for a protocol fixture.
  const double duration = request.dt * double(request.n_steps);
  std::array<double, 3> received{0.0, 0.0, 0.0};
  double kinetic = 0.0;
  double power = 0.0;  // with the one velocity Euler holds over the advance (SPEC.md §6.3)
  for (std::size_t k = 0; k < force.size(); ++k) {
    const double mass = kNodeMass + lumped[k / 3];
    velocity_[k] += force[k] / mass * duration;
    displacement_[k] += velocity_[k] * duration;
    received[k % 3] += force[k];
    power += force[k] * velocity_[k];
    kinetic += 0.5 * mass * velocity_[k] * velocity_[k];
  }
  monitors_ = {{"unbalanced_force_ratio", 0.0}, {"kinetic_energy_j", kinetic}, {"interface_force_received", received}, {"interface_power_w", power}};
  if (breakage_ == Breakage::no_force_monitor) monitors_.erase("interface_force_received");
  if (breakage_ == Breakage::nan_velocity) velocity_.back() = std::numeric_limits<double>::quiet_NaN();
  AdvanceResult result;
  result.monitors = monitors_;
  if (!interface_) return result;  // no interface, no outputs (SPEC.md §6.1)
  if (breakage_ == Breakage::wrong_output_shape) {
    result.outputs.push_back(Array::from_f64(field::velocity, {n, 2}, std::span(velocity_).first(static_cast<std::size_t>(2 * n))));
  } else {
    result.outputs.push_back(Array::from_f64(field::velocity, {n, 3}, velocity_));
  }
  result.outputs.push_back(Array::from_f64(field::displacement, {n, 3}, displacement_));
  return result;
}

std::vector<Array> FixtureBackend::snapshot(std::string& kind) {
  kind = "grid";
  const std::int64_t n = mesh_.node_count();
  return {Array::from_f64("node_position", {n, 3}, mesh_.coordinates), Array::from_f64("node_displacement", {n, 3}, displacement_),
          Array::from_f64("node_velocity", {n, 3}, velocity_), Array::from_i64("zone_nodes", {0, 8}, {}),
          Array::from_f64("zone_stress", {0, 6}, {})};
}

}  // namespace dfc::protocol::testing
