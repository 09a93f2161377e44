#pragma once
// ElasticReferenceBackend: an implicit, static, linear-elastic reference
// continuum (docs/theory/coupling.md §1). It reads the same section as fdm_server — so a
// scenario swaps the continuum by changing only `program` — builds the same
// mesh, supports and geostatic state with dfc_fdm, and answers every advance
// with the static equilibrium of those zones under the interface forces
// received (CondensedElasticContinuum).
//
// Provider role only (SPEC.md §6): advance takes `force` f64[n,3] (and accepts,
// then ignores, `mass`: a static solve has no inertia) and returns
// `displacement` u_I (total, relative to the initial geostatic state) and
// `velocity` = (u_I − u_I,previous)/(n_steps·Δt), the constant velocity that
// carries the partner's copy of the interface to u_I over the advance.
//
// Limits, by construction: quasi-static (no inertia, no waves, no damping, the
// interface jumps to equilibrium in one exchange), small strain, linear
// elasticity only (material.model = "elastic"; other models are refused).
#include <optional>

#include "dfc/fdm/fdm_config.hpp"
#include "dfc/protocol/solver_backend.hpp"
#include "dfc/reference/condensed_elastic_continuum.hpp"

namespace dfc::reference {

class ElasticReferenceBackend final : public protocol::SolverBackend {
 public:
  [[nodiscard]] protocol::SolverIdentity identity() const override;
  nlohmann::json configure(const nlohmann::json& section) override;
  protocol::InterfaceMesh interface_mesh() override;
  protocol::AdvanceResult advance(const protocol::AdvanceRequest& request) override;
  [[nodiscard]] nlohmann::json monitors() override;
  [[nodiscard]] std::vector<protocol::Array> snapshot(std::string& kind) override;

  /// The condensed system (after configure), for tests.
  [[nodiscard]] const CondensedElasticContinuum& condensed() const;

 private:
  [[nodiscard]] const fdm::FdmModel& model() const;

  std::optional<fdm::FdmModel> model_;  // mesh, supports and initial state; never stepped
  std::optional<CondensedElasticContinuum> condensed_;
  std::vector<double> interface_force_;        // last force received, f64 [n,3]
  Eigen::VectorXd interface_displacement_;     // u_I after the last advance
  std::int64_t step_ = 0;
  fdm::Vec3 interface_force_sum_ = fdm::Vec3::Zero();
  double interface_power_ = 0.0;
};

}  // namespace dfc::reference
