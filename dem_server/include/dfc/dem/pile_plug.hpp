#pragma once
// The soil column inside an open-ended tubular pile (the plug; Ciantia et al.
// 2024 §4, Fig. 1): its length L above the pile's tip, from which the plug
// length ratio PLR = L / h and the incremental filling ratio IFR = dL / dh
// follow (h the tip's depth below the original surface; IFR = 1: the soil
// enters as fast as the pile advances, unplugged; IFR = 0: fully plugged).
//
// The column's top is the highest particle top z + r, over the particles
// whose centres lie in the bore (closer to the axis than its radius) above
// the tip, that the next lower top follows within one largest diameter of
// those particles: a particle (or a few, spaced out) thrown up the tube and
// not resting on the column does not raise it.
#include <cstdint>

#include "dfc/dem/particle_store.hpp"
#include "dfc/dem/wall_builders.hpp"

namespace dfc::dem {

struct PlugColumn {
  double length = 0.0;         ///< m, top of the column minus tip_z; 0 with no particle in the bore
  std::int64_t particles = 0;  ///< particles whose centres lie in the bore above the tip
};

/// The column in the bore of `tube` (axis and inner_radius; the tube's current
/// tip at `tip_z`), from the particles' current positions.
[[nodiscard]] PlugColumn plug_column(const ParticleStore& particles, const CylinderGeometry& tube, double tip_z);

}  // namespace dfc::dem
