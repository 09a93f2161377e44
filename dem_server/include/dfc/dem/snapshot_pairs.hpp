#pragma once
// The pairs of a particle snapshot, drawn by the XDMF sidecar as lines
// between the two sphere centres (protocol/SPEC.md §6.4 allows arrays beyond
// the required ones, so no protocol change; docs/looking_at_a_run.md).
//
// Bonds: every pair that was ever bonded (bond_state.hpp), one row each:
//   bond_particle_index i64 [m,2]  rows of the two spheres in this snapshot's
//                                  particle arrays (the line's two nodes)
//   bond_particle_id    i64 [m,2]  their particle_id
//   bond_position       f64 [m,3]  m, the point between the surfaces on the centre line
//   bond_state          i64 [m]    1 intact, 2 damaged, 3 broken in tension, 4 broken in shear
//   bond_normal_force_n f64 [m]    N, the pair's force along the centre line, tension positive
//   bond_shear_force_n  f64 [m]    N, the magnitude of its part across the centre line
//   bond_opening_m      f64 [m]    m, surface gap |x_j - x_i| - r_i - r_j (negative: overlap)
//   bond_damage         f64 [m]    damage_bond only: D (1 once broken)
// The forces are the pair's total (bond and any contact part) of the last
// step; zero before the first step, when no force has been evaluated.
//
// Contacts: the force network, every pair of spheres whose force at the last
// step is not zero (touching, or held by a bond) and whose normal force is at
// least the threshold in magnitude (snapshot_contents.hpp), one row each:
//   contact_particle_index i64 [c,2]  rows of the two spheres (particle_id[row] names them)
//   contact_normal_force_n f64 [c]    N, the force along the centre line, compression
//                                     positive (force chains are compressive; a bond
//                                     in tension shows negative)
//   contact_force_n        f64 [c,3]  N, the whole force on the first sphere from the second
// None before the first step.
#include <vector>

#include "dfc/dem/simulation.hpp"
#include "dfc/protocol/array.hpp"

namespace dfc::dem {

/// Appends the bond arrays above to `arrays` (bonded laws only).
void append_bond_arrays(const Simulation& s, std::vector<protocol::Array>& arrays);

/// Appends the contact arrays above to `arrays`, the contacts whose normal
/// force is below `min_normal_force` (N) in magnitude left out.
void append_contact_arrays(const Simulation& s, double min_normal_force, std::vector<protocol::Array>& arrays);

}  // namespace dfc::dem
