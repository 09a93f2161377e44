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
//
// A body decomposed over many processes (issue "Beyond one machine") writes
// the same rows: each process collects those of the pairs whose first
// particle (the lower id) it owns, as a table with the two ids (PairRows);
// rank 0 gathers the tables, orders the rows by their ids and maps the ids
// to the rows of the snapshot's particle arrays (particle id order there).
// One process keeps its list order and slots.
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "dfc/dem/simulation.hpp"
#include "dfc/protocol/array.hpp"

namespace dfc::dem {

/// A snapshot's pairs as rows of doubles: the two particle ids first (their
/// bits, std::bit_cast: exact for any id), then the values of the kind.
struct PairRows {
  std::size_t width = 0;
  std::vector<double> values;
  [[nodiscard]] std::size_t size() const noexcept { return width == 0 ? 0 : values.size() / width; }
};

/// The bond rows of the pairs whose first particle is owned (`owned` per
/// slot; empty: every pair): ids, state, position (3), normal force, shear
/// force, opening, and the damage where the law has one (bond_damage_written).
[[nodiscard]] PairRows bond_rows(const Simulation& s, std::span<const std::uint8_t> owned);
/// The contact rows of the pairs whose first particle is owned (as
/// bond_rows) and whose normal force is at least `min_normal_force` (N) in
/// magnitude: ids, normal force (compression positive), force (3).
[[nodiscard]] PairRows contact_rows(const Simulation& s, double min_normal_force, std::span<const std::uint8_t> owned);
/// Whether bond rows carry the damage (damage_bond).
[[nodiscard]] bool bond_damage_written(const Simulation& s);
/// Orders `rows` by their first, then second id (the order of a body on many processes).
void sort_by_ids(PairRows& rows);

/// The row of each particle id in a snapshot's particle arrays.
class ParticleRows {
 public:
  explicit ParticleRows(std::span<const std::int64_t> ids);
  [[nodiscard]] std::int64_t operator()(std::int64_t id) const;

 private:
  std::vector<std::pair<std::int64_t, std::int64_t>> by_id_;  ///< (id, row), sorted
};

/// Appends the bond arrays above for `rows` (bond_rows), their index columns the rows `rows_of` gives.
void append_bond_arrays(const PairRows& rows, const ParticleRows& rows_of, bool with_damage, std::vector<protocol::Array>& arrays);
/// Appends the contact arrays above for `rows` (contact_rows).
void append_contact_arrays(const PairRows& rows, const ParticleRows& rows_of, std::vector<protocol::Array>& arrays);

/// The bond arrays of a body on one process, in its list order (bonded laws only).
void append_bond_arrays(const Simulation& s, std::vector<protocol::Array>& arrays);

/// The contact arrays of a body on one process, the contacts whose normal
/// force is below `min_normal_force` (N) in magnitude left out.
void append_contact_arrays(const Simulation& s, double min_normal_force, std::vector<protocol::Array>& arrays);

}  // namespace dfc::dem
