#pragma once
// The continuum_server scenario section (declared in
// dfc/common/sections/continuum_sections.hpp; `continuum_server --help`):
// the soil cylinder's mesh, the material (fdm_server's "material": the
// shared models and presets), the uniform initial stress and the rigid pile.
// Errors are dfc::ConfigError naming the key path in the section.
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "dfc/continuum/axisymmetric_solver.hpp"

namespace dfc::continuum {

struct PileModel {
  std::unique_ptr<AxisymmetricSolver> solver;  ///< not movable (its projections' factorisations)
  /// Penetration at which the pile stops and is held (absent: it never stops), m.
  std::optional<double> stop_depth;
  /// The pile's downward displacement per step while it moves, m.
  double pile_step = 0.0;
  /// Remesh when a triangle's area falls below this fraction of its area at creation.
  std::optional<double> remesh_below_area_ratio;
  /// The remesh's refinement bound on the smallest angle, degrees (0: the nodes only).
  double remesh_refine_deg = 0.0;
};

/// Builds the solver with its supports (axis: r held; side: r held;
/// base: z held), the initial stress and its boundary pressures, and the pile.
[[nodiscard]] PileModel load_pile_model(const nlohmann::json& section);

/// The --help text of the section.
[[nodiscard]] std::string continuum_config_help();

}  // namespace dfc::continuum
