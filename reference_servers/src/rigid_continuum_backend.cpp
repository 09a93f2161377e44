#include "dfc/reference/rigid_continuum_backend.hpp"

#include "dfc/common/version.hpp"
#include "dfc/protocol/monitor_units.hpp"

namespace dfc::reference {

protocol::SolverIdentity RigidContinuumBackend::identity() const {
  return {"rigid_continuum_server",
          std::string(project_version()),
          "continuum",
          {protocol::capability::provides_interface, protocol::capability::snapshot}};
}

nlohmann::json RigidContinuumBackend::configure(const nlohmann::json& section) {
  nlohmann::json info = geometry_.configure(section);
  // A rigid body has no stable-step limit: any dt is fine. It can only be the
  // side that provides the interface, whatever role the section names.
  info["dt_max"] = nullptr;
  info["capabilities"] = identity().capabilities;
  info[protocol::monitor_units_key] = protocol::shared_monitor_units();
  force_received_ = {0.0, 0.0, 0.0};
  return info;
}

protocol::InterfaceMesh RigidContinuumBackend::interface_mesh() {
  protocol::InterfaceMesh mesh = geometry_.interface_mesh();
  interface_nodes_ = mesh.node_count();
  return mesh;
}

protocol::AdvanceResult RigidContinuumBackend::advance(const protocol::AdvanceRequest& request) {
  protocol::AdvanceResult result;
  force_received_ = {0.0, 0.0, 0.0};
  // Fixed nodes ignore the lent mass, but it is an input of this side (SPEC.md §6.1).
  protocol::require_only(request.inputs, {protocol::field::force, protocol::field::mass}, "rigid_continuum_server");
  if (interface_nodes_ > 0) {
    const std::vector<double> force = protocol::require_f64(request.inputs, protocol::field::force, interface_nodes_, 3);
    // Summation in node order: deterministic, and the same order fdm_server uses.
    for (std::size_t i = 0; i < force.size(); ++i) force_received_[i % 3] += force[i];
    const std::vector<double> zeros(std::size_t(interface_nodes_) * 3, 0.0);
    result.outputs.push_back(protocol::Array::from_f64(protocol::field::velocity, {interface_nodes_, 3}, zeros));
    result.outputs.push_back(protocol::Array::from_f64(protocol::field::displacement, {interface_nodes_, 3}, zeros));
  }
  result.monitors = monitors();
  return result;
}

nlohmann::json RigidContinuumBackend::monitors() {
  return {{"unbalanced_force_ratio", 0.0},
          {"kinetic_energy_j", 0.0},
          {"interface_force_received", force_received_},
          {"interface_power_w", 0.0}};  // fixed nodes absorb no work
}

std::vector<protocol::Array> RigidContinuumBackend::snapshot(std::string& kind) { return geometry_.snapshot(kind); }

}  // namespace dfc::reference
