#pragma once
// The soil column inside an open-ended tubular pile (the plug; Ciantia et al.
// 2024 §4, Fig. 1): its length L above the pile's tip, from which the plug
// length ratio PLR = L / h and the incremental filling ratio IFR = dL / dh
// follow (h the tip's depth below the original surface; IFR = 1: the soil
// enters as fast as the pile advances, unplugged; IFR = 0: fully plugged).
//
// The column's top: the particles whose centres lie in the bore (closer to
// the axis than its radius) above the tip, taken from the highest top z + r
// down, until their volume reaches a quarter of the bore's volume over one
// largest diameter (about half a layer of a packing of porosity 0.5); the top
// of the particle that reaches it. A few particles thrown up the tube, or
// resting loose on the column, do not raise it; for a column that fills the
// bore it lies about half a layer below the highest top, by the same amount
// at every penetration (dL/dh is unbiased). A column of less volume than
// that is taken as empty (length 0).
#include <cstdint>
#include <span>
#include <vector>

#include "dfc/dem/particle_store.hpp"
#include "dfc/dem/wall_builders.hpp"

namespace dfc::dem {

/// Fraction of the bore's volume over one largest diameter that the loose top of the column may hold.
inline constexpr double plug_loose_fraction = 0.25;

struct PlugColumn {
  double length = 0.0;         ///< m, top of the column minus tip_z; 0 with no particle in the bore
  std::int64_t particles = 0;  ///< particles whose centres lie in the bore above the tip
};

/// A particle in the bore above the tip, as the column's top is found from it.
struct PlugTop {
  double z = 0.0;       ///< m, its top z + r
  double volume = 0.0;  ///< m3
  double radius = 0.0;  ///< m
};

/// The particles in the bore of `tube` (axis and inner_radius; the tube's
/// current tip at `tip_z`) among the slots `owned` marks (empty: all), in
/// slot order: one process's share of the column (dem_engine.hpp).
[[nodiscard]] std::vector<PlugTop> plug_tops(const ParticleStore& particles, const CylinderGeometry& tube, double tip_z,
                                             std::span<const std::uint8_t> owned = {});
/// The column of all the particles in the bore, in any order.
[[nodiscard]] PlugColumn plug_column_of(std::vector<PlugTop> tops, const CylinderGeometry& tube, double tip_z);
/// The column in the bore from the particles' current positions.
[[nodiscard]] PlugColumn plug_column(const ParticleStore& particles, const CylinderGeometry& tube, double tip_z);

}  // namespace dfc::dem
