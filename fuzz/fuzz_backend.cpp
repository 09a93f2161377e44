#include "fuzz_backend.hpp"

#include <algorithm>
#include <cmath>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/common/unstable_step_error.hpp"
#include "dfc/common/version.hpp"
#include "dfc/protocol/monitor_units.hpp"
#include "dfc/protocol/progress_monitors.hpp"
#include "square_grid_mesh.hpp"

namespace dfc::fuzz {

namespace {

using protocol::Array;
namespace field = protocol::field;

constexpr double kNodeMass = 1.0;  // kg, before any lumped mass from the other side
constexpr double kStiffness = 1e3;  // N/m, of the driven side's springs to the nodes' start positions

/// SPEC.md §6.1: a non-finite input value is BAD_ARRAY, decided before the solver runs.
void require_finite(const std::vector<double>& values, const char* name) {
  if (!std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); }))
    throw protocol::ProtocolError(protocol::ErrorCode::bad_array, std::string("array '") + name + "' holds a value that is not finite");
}

/// A state that is no longer finite is a solver failure (SPEC.md §7), as in the real solvers.
void require_finite_state(const std::vector<double>& values) {
  if (!std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); }))
    throw SolverError("the fuzz backend's state is no longer finite");
}

}  // namespace

protocol::SolverIdentity FuzzBackend::identity() const {
  return {"fuzz_backend",
          std::string(project_version()),
          "continuum",
          {protocol::capability::provides_interface, protocol::capability::accepts_interface, protocol::capability::snapshot}};
}

nlohmann::json FuzzBackend::configure(const nlohmann::json& section) {
  ConfigReader config(section, "");
  const std::int64_t side = config.integer("side", 2, 2, 4);
  dt_max_ = config.positive("dt_max", 1e-2);
  if (config.has("fail_after_steps")) fail_after_steps_ = config.integer("fail_after_steps", 0);
  else config.accept("fail_after_steps");
  (void)config.vec3("gravity_m_s2", {0.0, 0.0, 0.0});  // added by the coupler to every section (SPEC.md §4.2)
  config.finish();
  mesh_ = protocol::testing::square_grid_mesh(side);
  driven_ = false;
  velocity_.assign(mesh_.coordinates.size(), 0.0);
  displacement_.assign(mesh_.coordinates.size(), 0.0);
  monitors_ = nlohmann::json::object();
  const std::vector<protocol::ProgressMonitor> progress = {{"kinetic_energy_j", "energy", 1e3, "mJ"}};
  return {{"dt_suggested", dt_max_ / 2},
          {"dt_max", dt_max_},
          {protocol::monitor_units_key, protocol::shared_monitor_units()},
          {protocol::progress_monitors_key, protocol::to_json(progress)}};
}

void FuzzBackend::set_interface(const protocol::InterfaceMesh& mesh) {
  require_finite(mesh.coordinates, field::coordinates);
  mesh_ = mesh;
  driven_ = true;
  velocity_.assign(mesh_.coordinates.size(), 0.0);
  displacement_.assign(mesh_.coordinates.size(), 0.0);
}

protocol::AdvanceResult FuzzBackend::advance(const protocol::AdvanceRequest& request) {
  if (request.dt > dt_max_) throw UnstableStepError("dt exceeds the fuzz backend's stability limit", dt_max_);  // before anything changes
  const std::int64_t n = mesh_.node_count();
  const double duration = request.dt * double(request.n_steps);
  protocol::AdvanceResult result;
  if (driven_) {
    protocol::require_only(request.inputs, {field::velocity}, "a driven fuzz_backend");
    const std::vector<double> velocity = protocol::require_f64(request.inputs, field::velocity, n, 3);
    require_finite(velocity, field::velocity);
    if (fail_after_steps_ && request.first_step + request.n_steps > *fail_after_steps_) throw SolverError("fail_after_steps reached");
    std::vector<double> force(velocity.size());
    for (std::size_t k = 0; k < velocity.size(); ++k) {
      velocity_[k] = velocity[k];
      displacement_[k] += velocity[k] * duration;
      force[k] = -kStiffness * displacement_[k];
    }
    require_finite_state(displacement_);
    result.outputs.push_back(Array::from_f64(field::force, {n, 3}, force));
  } else {
    protocol::require_only(request.inputs, {field::force, field::mass}, "a providing fuzz_backend");
    const std::vector<double> force = protocol::require_f64(request.inputs, field::force, n, 3);
    require_finite(force, field::force);
    std::vector<double> lumped(static_cast<std::size_t>(n), 0.0);
    if (protocol::find_array(request.inputs, field::mass) != nullptr) {
      lumped = protocol::require_f64(request.inputs, field::mass, n, 0);
      require_finite(lumped, field::mass);
      if (!std::all_of(lumped.begin(), lumped.end(), [](double m) { return m >= 0.0; }))
        throw protocol::ProtocolError(protocol::ErrorCode::bad_array, "array 'mass' holds a negative mass");
    }
    if (fail_after_steps_ && request.first_step + request.n_steps > *fail_after_steps_) throw SolverError("fail_after_steps reached");
    for (std::size_t k = 0; k < force.size(); ++k) {
      velocity_[k] += force[k] / (kNodeMass + lumped[k / 3]) * duration;
      displacement_[k] += velocity_[k] * duration;
    }
    require_finite_state(velocity_);
    require_finite_state(displacement_);
    result.outputs.push_back(Array::from_f64(field::velocity, {n, 3}, velocity_));
    result.outputs.push_back(Array::from_f64(field::displacement, {n, 3}, displacement_));
  }
  double kinetic = 0.0;
  for (const double v : velocity_) kinetic += 0.5 * kNodeMass * v * v;
  if (!std::isfinite(kinetic)) throw SolverError("the fuzz backend's kinetic energy is no longer finite");
  monitors_ = {{"unbalanced_force_ratio", 0.0}, {"kinetic_energy_j", kinetic}};
  result.monitors = monitors_;
  return result;
}

std::vector<Array> FuzzBackend::snapshot(std::string& kind) {
  kind = "grid";
  const std::int64_t n = mesh_.node_count();
  return {Array::from_f64("node_position", {n, 3}, mesh_.coordinates), Array::from_f64("node_displacement", {n, 3}, displacement_),
          Array::from_f64("node_velocity", {n, 3}, velocity_)};
}

}  // namespace dfc::fuzz
