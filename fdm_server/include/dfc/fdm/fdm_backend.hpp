#pragma once
// FdmBackend: the FDM solver as a protocol v1 server backend.
//
// Coupling roles (section key coupling.role):
//  - provider: get_interface returns the coupling face group (node ids =
//    gridpoint indices, quads split into two triangles with normals out of the
//    continuum); advance takes `force` f64[n,3] (external force ON each
//    interface gridpoint, constant over the advance) and optionally `mass`
//    f64[n] (extra inertial mass, kept until replaced); it returns `velocity`
//    (end of advance) and `displacement`, both f64[n,3].
//  - driven: set_interface matches each received node to a gridpoint of the
//    group by coordinates; advance takes `velocity` f64[n,3], prescribed on
//    those gridpoints, and returns `force` f64[n,3] (force this body exerts on
//    each interface gridpoint, averaged over the advance) and `mass` f64[n]
//    (this body's inertial mass there for the advance's Δt).
//  - none: advance takes no inputs and returns none.
// Capabilities are announced before configure, so both interface capabilities
// are listed; the wrong one for the configured role answers `unsupported`.
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "dfc/fdm/fdm_config.hpp"
#include "dfc/protocol/solver_backend.hpp"

namespace dfc::fdm {

class FdmBackend final : public protocol::SolverBackend {
 public:
  [[nodiscard]] protocol::SolverIdentity identity() const override;
  nlohmann::json configure(const nlohmann::json& section) override;
  protocol::InterfaceMesh interface_mesh() override;
  void set_interface(const protocol::InterfaceMesh& mesh) override;
  protocol::AdvanceResult advance(const protocol::AdvanceRequest& request) override;
  [[nodiscard]] nlohmann::json monitors() override;
  [[nodiscard]] std::vector<protocol::Array> snapshot(std::string& kind) override;
  /// Capability checkpoint (fdm_checkpoint.cpp): the solver's running state and the interface monitors.
  [[nodiscard]] std::string checkpoint_state() override;
  void restore_state(std::string_view bytes) override;

 private:
  [[nodiscard]] Solver& solver();
  [[nodiscard]] std::vector<double> interface_rows(std::span<const Vec3> per_gridpoint) const;
  protocol::AdvanceResult advance_standalone(const protocol::AdvanceRequest& request);
  protocol::AdvanceResult advance_provider(const protocol::AdvanceRequest& request);
  protocol::AdvanceResult advance_driven(const protocol::AdvanceRequest& request);
  void run_steps(const protocol::AdvanceRequest& request, const std::function<void()>& after_each_step);

  std::optional<FdmModel> model_;
  std::vector<Index> interface_gridpoints_;  // row r of the interface arrays ↔ gridpoint
  bool interface_ready_ = false;
  Vec3 interface_force_sum_ = Vec3::Zero();  // provider: received; driven: reaction on this body
  double interface_power_ = 0.0;
};

}  // namespace dfc::fdm
