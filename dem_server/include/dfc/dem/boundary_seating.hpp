#pragma once
// Seating a trimmed generated body on a wall (docs/dem_generation.md §2).
//
// Trimming keeps whole spheres, so the outermost spheres of a replicated body
// stand up to a diameter off the floor and the coupling wall: the body would
// first fall onto the floor and, worse, nothing would hold its horizontal
// stress (an unconfined bonded body relaxes sigma_h to zero; the continuum's
// wall, a micrometre of elastic strain away, never reaches it). Seating moves
// each outermost sphere towards the wall, along the line from its centre to
// the nearest point of the wall, until it overlaps the wall by
//     delta = sigma_n (A / N) / k_n   (k_n the wall law's stiffness bound for
//                                      radius r: for a bonded law the contact's
//                                      and the bond's, about twice the unbonded
//                                      wall contact's, docs/dem_generation.md §9;
//                                      A / N the body's face area shared among
//                                      the N spheres seated on it),
// sigma_n = sigma_v where the wall faces up or down (the floor), sigma_h =
// K0 sigma_v where it stands (the sides; stress_profile.hpp), so the seated
// spheres carry the face's whole force from the start: a body that first had
// to settle onto its floor would hang part of its weight on the side walls by
// friction. A sphere moves only if its path is free: no other sphere that it
// would come closer to and overlap. A sphere that the trimming left
// overlapping the wall (by at most wall_contact_overlap_fraction of its
// radius) is backed off to touching and pressed the same way: its overlap
// would otherwise be a force that does not follow the g-level. Bond loads
// are stored history (stress_scaling.hpp), so moving a sphere does not change
// them; only its contact with the wall is new. The equilibration after
// generation evens out the shares. Done before the first step: on the rigid
// walls when the model is built, on the coupling wall when it arrives.
#include <cstddef>

#include "dfc/dem/bed_generator.hpp"
#include "dfc/dem/simulation.hpp"
#include "dfc/dem/stress_profile.hpp"
#include "dfc/dem/wall.hpp"

namespace dfc::dem {

struct SeatingReport {
  std::size_t seated = 0;
  double largest_move = 0.0;  ///< m
};

/// m2, the areas of the body's faces that walls bound.
struct FaceAreas {
  double floor = 0.0;  ///< the bottom (cross-section)
  double sides = 0.0;  ///< the lateral faces
};

/// The bottom and the lateral faces of a generation region.
[[nodiscard]] FaceAreas face_areas(const BedRegion& region);

/// Moves the outermost spheres of `simulation` onto `wall` (before the first step).
SeatingReport seat_on_wall(Simulation& simulation, const Wall& wall, const StressProfile& profile, const FaceAreas& faces);

}  // namespace dfc::dem
