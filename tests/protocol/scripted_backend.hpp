#pragma once
// ScriptedBackend: a SolverBackend for the ServerSession tests that records
// what the session passed it and fails on demand, so each test can drive one
// transition of SPEC.md §5.1 and see exactly what reached the solver.
#include <functional>
#include <optional>

#include "dfc/common/errors.hpp"
#include "dfc/protocol/solver_backend.hpp"

namespace dfc::protocol::testing {

class ScriptedBackend final : public SolverBackend {
 public:
  // What the session passed in.
  std::optional<nlohmann::json> configured_section;
  std::optional<InterfaceMesh> received_mesh;
  std::vector<AdvanceRequest> advances;

  // What to do. Each hook may throw to simulate a failure.
  std::function<void(const nlohmann::json&)> on_configure;
  std::function<void(const AdvanceRequest&)> on_advance;
  std::vector<std::string> capabilities{capability::provides_interface, capability::snapshot};

  [[nodiscard]] SolverIdentity identity() const override { return {"scripted", "9.9.9", "continuum", capabilities}; }

  nlohmann::json configure(const nlohmann::json& section) override {
    if (on_configure) on_configure(section);
    configured_section = section;
    return {{"dt_suggested", 0.5}, {"dt_max", nullptr}};
  }

  InterfaceMesh interface_mesh() override { return {{11, 12, 13}, {0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2}}; }

  void set_interface(const InterfaceMesh& mesh) override { received_mesh = mesh; }

  AdvanceResult advance(const AdvanceRequest& request) override {
    if (on_advance) on_advance(request);
    advances.push_back(request);
    AdvanceResult result;
    result.outputs.push_back(Array::from_f64(field::velocity, {1, 3}, std::vector<double>{1, 2, 3}));
    result.monitors = {{"kinetic_energy_j", 1.0}};
    return result;
  }

  [[nodiscard]] nlohmann::json monitors() override { return {{"kinetic_energy_j", 2.0}}; }

  [[nodiscard]] std::vector<Array> snapshot(std::string& kind) override {
    kind = "grid";
    return {Array::from_f64("node_position", {1, 3}, std::vector<double>{0, 0, 0})};
  }
};

}  // namespace dfc::protocol::testing
