#pragma once
// RigidContinuumBackend: the simplest reference continuum (docs/theory/coupling.md §1). It reads
// the same section as fdm_server — so a scenario swaps the continuum by
// changing only `program` — exposes the same interface mesh, and then holds the
// interface fixed: every velocity it returns is zero, whatever force it
// receives. A DEM run against it is the classic "rigid container" model, the
// limit of an infinitely stiff far field.
#include <optional>

#include "dfc/fdm/fdm_backend.hpp"
#include "dfc/protocol/solver_backend.hpp"

namespace dfc::reference {

class RigidContinuumBackend final : public protocol::SolverBackend {
 public:
  [[nodiscard]] protocol::SolverIdentity identity() const override;
  nlohmann::json configure(const nlohmann::json& section) override;
  protocol::InterfaceMesh interface_mesh() override;
  protocol::AdvanceResult advance(const protocol::AdvanceRequest& request) override;
  [[nodiscard]] nlohmann::json monitors() override;
  [[nodiscard]] std::vector<protocol::Array> snapshot(std::string& kind) override;

 private:
  /// Builds the mesh and the interface exactly as fdm_server does; never stepped.
  fdm::FdmBackend geometry_;
  std::int64_t interface_nodes_ = 0;
  std::array<double, 3> force_received_{0.0, 0.0, 0.0};
};

}  // namespace dfc::reference
