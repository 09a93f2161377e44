#pragma once
// The pile as a rigid flat foundation pushed into a generated body
// (docs/centrifuge_foundation.md; Zheng et al. 2023, Fig. 5–7).
//
//  - Start after equilibrium: with "pile.start_when": {"unbalanced_force_ratio": r}
//    the pile rests until the end of the first exchange, at or after its
//    start_step, at which the DEM's unbalanced-force ratio is at most r; it
//    moves at its velocity from the next step on. A generated body thus
//    settles under N g (docs/dem_generation.md §4) before it is loaded, in the
//    same run.
//  - Ramp: with "pile.ramp_steps": n the velocity rises linearly from 0 to
//    its value over the first n moving steps.
//  - Tip and shaft: the force of the particles on the pile split between the
//    facets of its flat end (the tip, facing the motion) and the others (the
//    shaft), each along -direction (positive resists penetration).
//  - Open-ended tube (pile.wall_thickness_m; Ciantia et al. 2024 §3): the tip
//    is the annulus, and the shaft splits into the inner shaft (facets facing
//    the axis: the plug's friction) and the outer shaft (the rest); each part
//    from its own facets, so that annulus + inner + outer = the pile force
//    up to the rounding of two summation orders.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "dfc/dem/vec3.hpp"
#include "dfc/dem/wall.hpp"

namespace dfc::dem {

/// "pile.start_when": when a resting pile starts.
struct PileStartRule {
  double unbalanced_force_ratio = 0.0;  ///< the DEM's unbalanced_force_ratio at most this
};

/// The pile's velocity `steps_moving` steps after it started (0 at its first
/// moving step): `velocity` raised linearly over `ramp_steps` steps, so that the
/// rigid foundation does not strike the rock at full speed (a velocity jump v
/// sends a stress wave of about rho c v into it), then constant.
[[nodiscard]] Vec3 ramped_velocity(const Vec3& velocity, std::int64_t steps_moving, std::int64_t ramp_steps);

/// True once `rule` lets the pile start: `step` has reached `start_step` and
/// the DEM's unbalanced-force ratio is at most the rule's.
[[nodiscard]] bool pile_may_start(const PileStartRule& rule, std::int64_t step, std::int64_t start_step, double unbalanced_force_ratio);

/// Facets of `pile` whose outward normal points along `direction` (the flat
/// end that leads the motion): within 1e-6 of parallel.
[[nodiscard]] std::vector<std::size_t> pile_tip_facets(const Wall& pile, const Vec3& direction);

/// Facets of `pile` whose outward normal points towards the vertical axis
/// through (axis_x, axis_y) (the bore of an open tube; none on a closed
/// cylinder): the normal's horizontal part has a negative dot product with the
/// facet centroid's offset from the axis.
[[nodiscard]] std::vector<std::size_t> pile_inner_facets(const Wall& pile, double axis_x, double axis_y);

/// The facets of `pile` in neither `tip` nor `inner` (sorted lists): the outer shaft.
[[nodiscard]] std::vector<std::size_t> other_facets(const Wall& pile, std::span<const std::size_t> tip, std::span<const std::size_t> inner);

/// Sum of the per-facet forces (`Wall::facet_force`, the particles ON the
/// wall) over `facets`.
[[nodiscard]] Vec3 facets_force(const Wall& wall, std::span<const std::size_t> facets);

}  // namespace dfc::dem
