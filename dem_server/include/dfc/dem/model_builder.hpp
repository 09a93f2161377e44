#pragma once
// From a validated DEM section to a ready Simulation: walls, pile, particles
// and the time step.
#include <cstddef>
#include <memory>
#include <optional>

#include "dfc/dem/dem_config.hpp"
#include "dfc/dem/sample_preparation.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

struct DemModel {
  std::unique_ptr<Simulation> simulation;
  std::optional<std::size_t> pile_wall;  ///< index of the pile among the walls
  double dt = 0.0;                       ///< s, the chosen step
  double dt_critical = 0.0;              ///< s, including the wall_contact law (the coupling wall comes later)
  std::size_t removed_particles = 0;     ///< generated spheres dropped because they overlapped a wall or the pile
  std::optional<PreparationReport> preparation;  ///< periodic cell with radius expansion or consolidation
  double max_strain_rate = 0.0;          ///< 1/s, the cell servo's cap (periodic cell)
};

/// Throws ConfigError("timestep.dt_s") if a fixed dt exceeds the critical step.
/// With a periodic cell that has radius expansion or a consolidation, runs the
/// preparation (sample_preparation.hpp) before returning.
[[nodiscard]] DemModel build_model(const DemConfig& config);

}  // namespace dfc::dem
