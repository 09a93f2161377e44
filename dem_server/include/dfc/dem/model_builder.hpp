#pragma once
// From a validated DEM section to a ready Simulation: the layout (spheres and
// walls, model_layout.hpp), walls, pile, particles, the time step, and the
// loading protocols (loading_protocol.hpp) prepared.
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "dfc/dem/dem_config.hpp"
#include "dfc/dem/loading_protocol.hpp"
#include "dfc/dem/sample_preparation.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

struct DemModel {
  std::unique_ptr<Simulation> simulation;
  std::optional<std::size_t> pile_wall;  ///< index of the pile among the walls
  double dt = 0.0;                       ///< s, the chosen step
  double dt_critical = 0.0;              ///< s, including the wall_contact law (the coupling wall comes later)
  std::size_t removed_particles = 0;     ///< generated spheres dropped because a wall cut them (overlap > 1e-3 R) or they were inside the pile
  std::optional<PreparationReport> preparation;  ///< periodic cell with radius expansion or consolidation
  double max_strain_rate = 0.0;          ///< 1/s, the servo's cap (periodic cell, triaxial walls)
  std::optional<GeneratedBody> generation;  ///< generator "pcrm": the REV, the replication and the stress scaling
  std::vector<std::unique_ptr<LoadingProtocol>> loading;  ///< the experiments the section enables, prepared
};

/// Throws ConfigError("timestep.dt_s") if a fixed dt exceeds the critical step.
/// Runs every loading protocol's prepare before returning: a periodic cell
/// with radius expansion or a consolidation is prepared
/// (sample_preparation.hpp), and so is a triaxial section (confinement in the
/// walls, then bonds).
[[nodiscard]] DemModel build_model(const DemConfig& config);

}  // namespace dfc::dem
