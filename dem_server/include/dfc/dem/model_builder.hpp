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
  std::size_t removed_particles = 0;     ///< generated spheres dropped because a wall cut them (overlap > 1e-3 R) or they were inside the pile
  std::optional<PreparationReport> preparation;  ///< periodic cell with radius expansion or consolidation
  double max_strain_rate = 0.0;          ///< 1/s, the servo's cap (periodic cell, triaxial walls)
  std::optional<GeneratedBody> generation;  ///< generator "pcrm": the REV, the replication and the stress scaling
};

/// The servo of a triaxial section's confinement stage: every wall at sigma_3.
[[nodiscard]] TriaxialControl triaxial_confinement(const TriaxialConfig& config, double max_strain_rate);
/// ... and of its shearing stage: the platens close at rate H0/2 each (H0 the
/// platen separation at the end of the confinement), the lateral walls at sigma_3.
[[nodiscard]] TriaxialControl triaxial_shearing(const TriaxialConfig& config, double max_strain_rate, double initial_height);

/// Throws ConfigError("timestep.dt_s") if a fixed dt exceeds the critical step.
/// With a periodic cell that has radius expansion or a consolidation, runs the
/// preparation (sample_preparation.hpp) before returning; so does a triaxial
/// section (confinement in the walls, then bonds).
[[nodiscard]] DemModel build_model(const DemConfig& config);

}  // namespace dfc::dem
