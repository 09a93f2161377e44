#pragma once
// The state of a bond, stored by every bonded law in history column 0.
//
// Why a history column: the state must travel with the contact's history
// through neighbour-list rebuilds (contact_lists.hpp HistoryArchive), and a
// non-zero state is what makes a pair persistent (simulation.cpp re-adds every
// pair whose state is not `none` to the candidate list, however far apart the
// particles have moved). Broken bonds stay persistent too, so that the counts
// of broken bonds are cumulative for the whole run.
#include <cstddef>
#include <cstdint>

namespace dfc::dem {

enum class BondState : std::uint8_t {
  none = 0,            ///< never bonded: the law's unbonded (linear frictional) contact
  intact = 1,          ///< bonded, undamaged
  damaged = 2,         ///< bonded, softening (soft_bond) or D > 0 (damage_bond)
  broken_tension = 3,  ///< the bond failed in tension; unbonded contact since
  broken_shear = 4,    ///< the bond failed in shear (damage_bond: any other dominant mode); unbonded contact since
};

/// History column of the bond state in every bonded law.
inline constexpr std::size_t bond_state_column = 0;

[[nodiscard]] inline BondState bond_state(const double* history) noexcept { return BondState(std::uint8_t(history[bond_state_column])); }
inline void set_bond_state(double* history, BondState s) noexcept { history[bond_state_column] = double(std::uint8_t(s)); }
/// A bond that still carries load (intact or damaged).
[[nodiscard]] inline bool is_bonded(BondState s) noexcept { return s == BondState::intact || s == BondState::damaged; }

/// Bonds by state over the particle pairs (the DEM monitors "bonds_*").
struct BondCounts {
  std::int64_t intact = 0;
  std::int64_t damaged = 0;
  std::int64_t broken_tension = 0;
  std::int64_t broken_shear = 0;
};

}  // namespace dfc::dem
