#pragma once
// Whole-model measurements of the DEM (monitors of the server).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "dfc/dem/exact_sum.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

struct Measurements {
  std::size_t particle_count = 0;
  std::size_t pair_contact_count = 0;  ///< particle–particle contacts carrying a force
  std::size_t wall_contact_count = 0;  ///< particle–facet contacts carrying a force
  double coordination_number = 0.0;    ///< (2 pair + wall contacts) / particles
  double kinetic_energy = 0.0;         ///< J, translational + rotational, from the stored half-step velocities
  double total_weight = 0.0;           ///< N, sum of m |g|
  /// DEM analogue of FLAC's average unbalanced-force ratio: mean over particles
  /// of |sum of contact forces + m g| (the undamped resultant of the last step)
  /// divided by the mean |force| of the force-carrying contacts. Without
  /// contacts the denominator is the mean weight (free fall reads 1); 0 when
  /// nothing acts at all. Tends to 0 at equilibrium (PFC reports ~1e-5 as settled).
  double unbalanced_force_ratio = 0.0;
  // After a step that failed in the middle of a run (partial contact outputs,
  // Simulation::contact_outputs_complete() false) the contact counts are 0 and
  // coordination_number and unbalanced_force_ratio are NaN: unknown.

  [[nodiscard]] std::size_t contact_count() const noexcept { return pair_contact_count + wall_contact_count; }
};

[[nodiscard]] Measurements measure(const Simulation& simulation);

/// What a measurement is summed from, unrounded: the sums of a decomposed
/// run's processes add up (limbs and counts) to the whole body's, so its
/// measurement has the whole body's bits (distributed_simulation.hpp).
struct MeasureSums {
  /// kinetic energy, weight, |unbalanced force| over the particles; |force| over the contacts
  std::array<ExactSum, 4> sums{};
  std::int64_t particles = 0, pair_contacts = 0, wall_contacts = 0;
  bool outputs_complete = true;
};
/// The sums over the particles `owned` marks (by slot; empty: all of them),
/// the pair contacts of the owned first particles and the wall contacts of
/// owned particles.
[[nodiscard]] MeasureSums measure_sums(const Simulation& simulation, std::span<const std::uint8_t> owned = {});
[[nodiscard]] Measurements measurements_from(const MeasureSums& sums);

}  // namespace dfc::dem
