#include "dfc/fdm/fdm_backend.hpp"

#include <algorithm>
#include <cmath>

#include "dfc/common/errors.hpp"
#include "dfc/common/unstable_step_error.hpp"
#include "dfc/common/version.hpp"
#include "dfc/fdm/grid_snapshot.hpp"
#include "dfc/fdm/interface_matching.hpp"
#include "dfc/fdm/provider_interface.hpp"
#include "dfc/protocol/monitor_units.hpp"

namespace dfc::fdm {

namespace {

using protocol::Array;
using protocol::ErrorCode;
using protocol::ProtocolError;

// Interface nodes match when every coordinate agrees to 1e-9 × model size:
// far above round-off of generated coordinates, far below any zone size.
constexpr double kMatchTolerance = 1e-9;

const char* role_name(CouplingRole role) {
  switch (role) {
    case CouplingRole::provider: return "provider";
    case CouplingRole::driven: return "driven";
    case CouplingRole::none: break;
  }
  return "none (standalone)";
}

Vec3 row(const std::vector<double>& values, std::size_t r) { return {values[3 * r], values[3 * r + 1], values[3 * r + 2]}; }

nlohmann::json to_json(const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

}  // namespace

protocol::SolverIdentity FdmBackend::identity() const {
  return {"fdm_server", std::string(project_version()), "continuum",
          {protocol::capability::provides_interface, protocol::capability::accepts_interface, protocol::capability::snapshot,
           protocol::capability::checkpoint}};
}

nlohmann::json FdmBackend::configure(const nlohmann::json& section) {
  model_.emplace(load_fdm_model(section));
  interface_gridpoints_.clear();
  interface_ready_ = false;
  const CouplingSettings& coupling = model_->coupling;
  if (coupling.role == CouplingRole::provider) {
    interface_gridpoints_ = solver().mesh().face_group_gridpoints(coupling.group);
    interface_ready_ = true;
  }
  const double dt_critical = solver().critical_timestep();
  nlohmann::json info = {{"dt_suggested", dt_critical},
                         {"dt_max", solver().settings().mass_scaling ? nlohmann::json(nullptr) : nlohmann::json(dt_critical)},
                         {"gridpoints", solver().mesh().gridpoint_count()},
                         {"zones", solver().mesh().zone_count()},
                         {"coupling_role", coupling.role == CouplingRole::none ? "none" : role_name(coupling.role)}};
  if (coupling.role == CouplingRole::provider) info["interface_nodes"] = interface_gridpoints_.size();
  // hello announces both interface capabilities (the role is only known now);
  // these are the ones this configured session actually serves.
  info["capabilities"] = nlohmann::json::array();
  if (coupling.role == CouplingRole::provider) info["capabilities"].push_back(protocol::capability::provides_interface);
  if (coupling.role == CouplingRole::driven) info["capabilities"].push_back(protocol::capability::accepts_interface);
  info["capabilities"].push_back(protocol::capability::snapshot);
  info["capabilities"].push_back(protocol::capability::checkpoint);
  // The monitors SPEC.md §6.3 defines for every server, and the grid's
  // support reaction and weight (the whole-model weight balance).
  nlohmann::json units = protocol::shared_monitor_units();
  units["support_reaction_n"] = protocol::unit::newton;
  units["total_weight_n"] = protocol::unit::newton;
  info[protocol::monitor_units_key] = units;
  return info;
}

Solver& FdmBackend::solver() {
  if (!model_) throw ProtocolError(ErrorCode::out_of_order, "fdm_server is not configured yet; send configure first");
  return model_->solver;
}

protocol::InterfaceMesh FdmBackend::interface_mesh() {
  const Solver& s = solver();
  if (model_->coupling.role != CouplingRole::provider)
    throw ProtocolError(ErrorCode::unsupported, std::string("get_interface needs coupling.role = \"provider\"; this fdm_server is ") +
                                                    role_name(model_->coupling.role));
  return provider_interface_mesh(s.mesh(), interface_gridpoints_, model_->coupling.group);
}

void FdmBackend::set_interface(const protocol::InterfaceMesh& mesh) {
  Solver& s = solver();
  if (model_->coupling.role != CouplingRole::driven)
    throw ProtocolError(ErrorCode::unsupported, std::string("set_interface needs coupling.role = \"driven\"; this fdm_server is ") +
                                                    role_name(model_->coupling.role));
  if (mesh.coordinates.size() != 3 * mesh.node_ids.size())
    throw ProtocolError(ErrorCode::bad_array, "interface 'coordinates' must be f64 [" + std::to_string(mesh.node_ids.size()) + ",3]");
  const std::vector<Index> candidates = s.mesh().face_group_gridpoints(model_->coupling.group);
  try {
    interface_gridpoints_ = match_nodes_to_gridpoints(s.mesh(), candidates, mesh.node_ids, mesh.coordinates, kMatchTolerance * s.mesh().size());
  } catch (const UserError& e) {
    throw ProtocolError(ErrorCode::bad_array, "set_interface: " + std::string(e.what()) + " (face group \"" + model_->coupling.group + "\")");
  }
  // Held at rest until the first advance prescribes their velocities.
  for (const Index gp : interface_gridpoints_) s.prescribe_velocity(gp, Vec3::Zero());
  interface_ready_ = true;
}

std::vector<double> FdmBackend::interface_rows(std::span<const Vec3> per_gridpoint) const {
  std::vector<double> values;
  values.reserve(3 * interface_gridpoints_.size());
  for (const Index gp : interface_gridpoints_) values.insert(values.end(), {per_gridpoint[gp].x(), per_gridpoint[gp].y(), per_gridpoint[gp].z()});
  return values;
}

void FdmBackend::run_steps(const protocol::AdvanceRequest& request, const std::function<void()>& after_each_step) {
  Solver& s = solver();
  for (std::int64_t k = 0; k < request.n_steps; ++k) {
    s.step(request.dt);
    after_each_step();
  }
}

protocol::AdvanceResult FdmBackend::advance(const protocol::AdvanceRequest& request) {
  if (!model_) throw ProtocolError(ErrorCode::out_of_order, "fdm_server is not configured yet; send configure first");
  // Refused before any input is applied (SPEC.md §5.2): the reply carries the largest stable step, and nothing changes.
  if (const auto reason = solver().unstable_step_reason(request.dt)) throw UnstableStepError(*reason, solver().critical_timestep());
  switch (model_->coupling.role) {
    case CouplingRole::provider: return advance_provider(request);
    case CouplingRole::driven: return advance_driven(request);
    case CouplingRole::none: break;
  }
  return advance_standalone(request);
}

protocol::AdvanceResult FdmBackend::advance_standalone(const protocol::AdvanceRequest& request) {
  protocol::require_only(request.inputs, {}, "a standalone fdm_server (no coupling section)");
  run_steps(request, [] {});
  return {{}, monitors()};
}

protocol::AdvanceResult FdmBackend::advance_provider(const protocol::AdvanceRequest& request) {
  Solver& s = solver();
  const auto n = std::int64_t(interface_gridpoints_.size());
  const ProviderInputs received = read_provider_inputs(request.inputs, n, "a provider fdm_server");
  const std::vector<double>& force = received.force;
  if (received.mass)
    for (std::size_t r = 0; r < received.mass->size(); ++r) s.set_extra_mass(interface_gridpoints_[r], (*received.mass)[r]);
  interface_force_sum_ = Vec3::Zero();
  for (std::size_t r = 0; r < interface_gridpoints_.size(); ++r) {
    s.set_external_force(interface_gridpoints_[r], row(force, r));
    interface_force_sum_ += row(force, r);
  }

  std::vector<Vec3> velocity_sum(interface_gridpoints_.size(), Vec3::Zero());
  run_steps(request, [&] {
    for (std::size_t r = 0; r < interface_gridpoints_.size(); ++r) velocity_sum[r] += s.velocities()[interface_gridpoints_[r]];
  });
  // Power of the received forces with the velocity averaged over the advance.
  interface_power_ = 0.0;
  for (std::size_t r = 0; r < interface_gridpoints_.size(); ++r)
    interface_power_ += row(force, r).dot(velocity_sum[r] / double(request.n_steps));

  protocol::AdvanceResult result;
  result.outputs.push_back(Array::from_f64(protocol::field::velocity, {n, 3}, interface_rows(s.velocities())));
  result.outputs.push_back(Array::from_f64(protocol::field::displacement, {n, 3}, interface_rows(s.displacements())));
  result.monitors = monitors();
  return result;
}

protocol::AdvanceResult FdmBackend::advance_driven(const protocol::AdvanceRequest& request) {
  Solver& s = solver();
  if (!interface_ready_)
    throw ProtocolError(ErrorCode::out_of_order, "a driven fdm_server needs set_interface (the partner's interface mesh) before advance");
  const auto n = std::int64_t(interface_gridpoints_.size());
  protocol::require_only(request.inputs, {protocol::field::velocity}, "a driven fdm_server");
  const std::vector<double> velocity = protocol::require_f64(request.inputs, protocol::field::velocity, n, 3);
  require_finite(velocity, protocol::field::velocity);
  for (std::size_t r = 0; r < interface_gridpoints_.size(); ++r) s.prescribe_velocity(interface_gridpoints_[r], row(velocity, r));

  // Impulse-preserving output: the force this body exerts on each interface
  // gridpoint, averaged over the steps of the advance (docs/theory/coupling.md §3).
  std::vector<Vec3> force_sum(interface_gridpoints_.size(), Vec3::Zero());
  run_steps(request, [&] {
    for (std::size_t r = 0; r < interface_gridpoints_.size(); ++r) force_sum[r] += s.force_exerted_on_gridpoint(interface_gridpoints_[r]);
  });
  std::vector<double> force(3 * interface_gridpoints_.size());
  std::vector<double> mass(interface_gridpoints_.size());
  interface_force_sum_ = Vec3::Zero();
  interface_power_ = 0.0;
  for (std::size_t r = 0; r < interface_gridpoints_.size(); ++r) {
    const Vec3 average = force_sum[r] / double(request.n_steps);
    for (Eigen::Index c = 0; c < 3; ++c) force[3 * r + std::size_t(c)] = average[c];
    mass[r] = s.inertial_mass(interface_gridpoints_[r], request.dt);
    interface_force_sum_ -= average;  // reaction: force the interface exerts on this body
    interface_power_ += average.dot(row(velocity, r));
  }

  protocol::AdvanceResult result;
  result.outputs.push_back(Array::from_f64(protocol::field::force, {n, 3}, force));
  result.outputs.push_back(Array::from_f64(protocol::field::mass, {n}, mass));
  result.monitors = monitors();
  return result;
}

nlohmann::json FdmBackend::monitors() {
  const Solver& s = solver();
  nlohmann::json m = {{"unbalanced_force_ratio", s.unbalanced_force_ratio()},
                      {"kinetic_energy_j", s.kinetic_energy()},
                      {"step", s.step_count()},
                      {"support_reaction_n", to_json(s.support_reaction())},
                      {"total_weight_n", s.total_body_force().norm()}};
  if (model_->coupling.role == CouplingRole::provider) {
    m["interface_force_received"] = to_json(interface_force_sum_);
    m["interface_power_w"] = interface_power_;
  } else if (model_->coupling.role == CouplingRole::driven) {
    m["interface_force_reaction"] = to_json(interface_force_sum_);
    m["interface_power_w"] = interface_power_;
  }
  return m;
}

std::vector<protocol::Array> FdmBackend::snapshot(std::string& kind) {
  const Solver& s = solver();
  kind = "grid";
  std::vector<Stress> zone_stress(s.mesh().zone_count());
  for (Index z = 0; z < s.mesh().zone_count(); ++z) zone_stress[z] = s.zone_stress(z);
  return grid_snapshot(s.mesh(), s.displacements(), s.velocities(), zone_stress, s.external_forces());
}

}  // namespace dfc::fdm
