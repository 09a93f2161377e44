#pragma once
// FixtureBackend: the smallest honest continuum, for testing dfc_conformance
// itself. Its interface is a unit-spaced square grid of side × side nodes in
// z = 0; each node has 1 kg and moves under the force it is given. A
// Breakage makes it violate the contract in one known way, so a test can
// show the checker notices.
#include <optional>
#include <string_view>

#include "dfc/protocol/message.hpp"
#include "dfc/protocol/solver_backend.hpp"

namespace dfc::protocol::testing {

enum class Breakage {
  none,
  throw_in_advance,    ///< advance throws std::runtime_error (an INTERNAL error reply)
  wrong_output_shape,  ///< advance returns velocity [n,2] instead of [n,3]
  crash_in_advance,    ///< advance aborts the process
  hang_in_advance,     ///< advance never returns
  no_force_monitor,    ///< advance omits the monitor interface_force_received
  nan_velocity,        ///< advance returns a NaN in its velocity
  huge_particle_count,  ///< monitors claim 2e10 particles, more than any snapshot could hold
  unsent_progress_monitor,      ///< configure lists a progress monitor the server never sends
  malformed_progress_monitors,  ///< configure's info.progress_monitors is not an array
  no_heartbeat,                 ///< declares the current minor but runs no heartbeat (SPEC.md §9.1)
  no_authentication,            ///< declares the current minor but ignores DFC_KEY_FILE (SPEC.md §2.1)
  accepts_surplus_input,        ///< advances despite an input array it does not take (SPEC.md §6.1, 1.1)
  deadlock_in_advance,          ///< advance blocks forever, doing no work, while the heartbeat answers (SPEC.md §9.1, 1.8)
  no_progress                   ///< declares the current minor but its pongs carry no progress (SPEC.md §9.1, 1.8)
};

/// "throw", "shape", "crash", "hang", "no-force-monitor", "nan-velocity", "huge-particle-count", "unsent-progress-monitor",
/// "malformed-progress-monitors", "no-heartbeat", "no-authentication", "accept-surplus-input", "deadlock-advance",
/// "no-progress"; nullopt for anything else.
[[nodiscard]] std::optional<Breakage> breakage_from_name(std::string_view name) noexcept;

class FixtureBackend final : public SolverBackend {
 public:
  /// `declared_minor`: the minor of the server it plays; below 1.1 it takes
  /// surplus input arrays silently, below 1.2 it declares no monitor_units,
  /// below 1.5 no progress_monitors (SPEC.md §1).
  explicit FixtureBackend(Breakage breakage = Breakage::none, int declared_minor = kVersionMinor)
      : breakage_(breakage), declared_minor_(declared_minor) {}

  [[nodiscard]] SolverIdentity identity() const override;
  nlohmann::json configure(const nlohmann::json& section) override;
  InterfaceMesh interface_mesh() override { return mesh_; }
  AdvanceResult advance(const AdvanceRequest& request) override;
  [[nodiscard]] nlohmann::json monitors() override { return monitors_; }
  [[nodiscard]] std::vector<Array> snapshot(std::string& kind) override;

 private:
  Breakage breakage_;
  int declared_minor_;
  double advance_seconds_ = 0.0;  ///< section key advance_s: how long each advance takes (a slow solver)
  bool interface_ = true;         ///< section key interface: false narrows the capabilities to snapshot (a run alone)
  InterfaceMesh mesh_;
  std::vector<double> velocity_;      ///< m/s, 3 per node
  std::vector<double> displacement_;  ///< m, 3 per node
  nlohmann::json monitors_ = nlohmann::json::object();
};

}  // namespace dfc::protocol::testing
