#pragma once
// FuzzBackend: a small deterministic solver behind the ServerSession that the
// protocol fuzzer drives, so that decoded messages reach every state of
// SPEC.md §5.1 without a real solver's cost.
//
// It models a side × side grid of 1 kg nodes in z = 0. Provided interface
// (default): advance takes `force` [n,3] (and optional `mass` [n]) and returns
// `velocity` and `displacement`. After set_interface it is the driven side:
// advance takes `velocity` [n,3] of the received mesh and returns `force`.
// Section keys, all optional: side (2-4), dt_max (s, the step refused as
// unstable above it), fail_after_steps (a SolverError once the step count
// would pass it: the way into the failed state), gravity_m_s2.
//
// It lacks capability `checkpoint` on purpose: checkpoint and restore write
// and read the file named in the request, and a fuzzer must not write files
// at paths it invents.
#include <cstdint>
#include <optional>

#include "dfc/protocol/solver_backend.hpp"

namespace dfc::fuzz {

class FuzzBackend final : public protocol::SolverBackend {
 public:
  [[nodiscard]] protocol::SolverIdentity identity() const override;
  nlohmann::json configure(const nlohmann::json& section) override;
  protocol::InterfaceMesh interface_mesh() override { return mesh_; }
  void set_interface(const protocol::InterfaceMesh& mesh) override;
  protocol::AdvanceResult advance(const protocol::AdvanceRequest& request) override;
  [[nodiscard]] nlohmann::json monitors() override { return monitors_; }
  [[nodiscard]] std::vector<protocol::Array> snapshot(std::string& kind) override;

 private:
  protocol::InterfaceMesh mesh_;
  bool driven_ = false;  ///< set_interface received a mesh: velocity in, force out
  double dt_max_ = 1e-2;
  std::optional<std::int64_t> fail_after_steps_;
  std::vector<double> velocity_;      ///< m/s, 3 per node
  std::vector<double> displacement_;  ///< m, 3 per node
  nlohmann::json monitors_ = nlohmann::json::object();
};

}  // namespace dfc::fuzz
