#pragma once
// ContinuumBackend: the axisymmetric continuum of the jacked open-ended pile
// (continuum_config.hpp) as a protocol v1 server backend.
//
// A single-participant model: it neither provides nor accepts an interface
// (advance takes no inputs and returns none) and cannot write checkpoints,
// so it announces only `snapshot`. Each step moves the pile by pile.step_m
// (quasi-static pseudo-time, mass scaling: any dt is stable, dt only labels
// the steps) until pile.depth_m; after an advance in which a triangle's
// area fell below mesh.remesh_below_area_ratio of its area when it was made
// the nodes are re-triangulated (AxisymmetricSolver::remesh, refined to
// mesh.remesh_refine_deg; an added node's reference position is where it
// was added). Monitors (SPEC.md §6.3): the shared ones,
// the pile's force split by face, its penetration, the plug length and the
// base's reaction. Snapshot: kind "grid" with the nodes in the meridian plane
// y = 0 (x = r) and the triangles as extra arrays.
#include <optional>
#include <vector>

#include "dfc/continuum/continuum_config.hpp"
#include "dfc/protocol/solver_backend.hpp"

namespace dfc::continuum {

class ContinuumBackend final : public protocol::SolverBackend {
 public:
  [[nodiscard]] protocol::SolverIdentity identity() const override;
  nlohmann::json configure(const nlohmann::json& section) override;
  protocol::AdvanceResult advance(const protocol::AdvanceRequest& request) override;
  [[nodiscard]] nlohmann::json monitors() override;
  [[nodiscard]] std::vector<protocol::Array> snapshot(std::string& kind) override;

 private:
  [[nodiscard]] PileModel& model();
  /// The pile's soil plug: mean height of the bore's surface nodes above the tip, m.
  [[nodiscard]] double plug_length() const;

  std::optional<PileModel> model_;
  std::vector<Point> reference_nodes_;  ///< node positions at configure
  std::vector<Index> bore_surface_;     ///< surface nodes inside the tube at configure
  double dt_ = 1.0;                     ///< s per step of the last advance (labels the velocities)
  double peak_force_ = 0.0;
  int remeshes_ = 0;
};

}  // namespace dfc::continuum
