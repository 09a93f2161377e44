#pragma once
// The first stage of building a DEM model from a read section: where the
// spheres and the walls are before the simulation exists.
//
//   1. spheres: the generator's ("lattice": the bed; "list": as given;
//      "radius_expansion" in a periodic cell: placed at their start radii;
//      "pcrm": none here, the model builder generates the body)
//   2. walls: a plane wall without half_size_m gets a square covering the
//      spheres' bounding box seen from its point (the region's box for pcrm)
//   3. the loading protocols arrange their walls (LoadingProtocol::arrange:
//      platens seated on the particles, set moving at a strain rate)
//   4. "radius_expansion" inside the six walls of a triaxial section: the
//      spheres placed in the box the walls bound, as they stand
// Errors are ConfigError naming the key to change.
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "dfc/dem/dem_config.hpp"
#include "dfc/dem/loading_protocol.hpp"

namespace dfc::dem {

struct ModelLayout {
  std::vector<GeneratedSphere> spheres;  ///< id = index; a radius expansion's at their start radii
  std::vector<double> final_radius;      ///< m, a radius expansion's final radii by id (empty otherwise)
  std::vector<WallConfig> walls;         ///< the section's walls, meshed, sized and arranged
};

/// Stages 1–4 with the given protocols (make_loading_protocols(config)).
[[nodiscard]] ModelLayout lay_out_model(const DemConfig& config, std::span<const std::unique_ptr<LoadingProtocol>> protocols);
/// Stages 1–4 with the protocols the section enables.
[[nodiscard]] ModelLayout lay_out_model(const DemConfig& config);

/// Moves both walls along `axis` until each touches the outermost particle
/// surface (support function max/min of c.a ± r): `high` onto the highest,
/// `low` onto the lowest, so that loading starts at once instead of after
/// closing the margin to the region faces.
void seat_on_particles(WallConfig& high, WallConfig& low, std::span<const GeneratedSphere> spheres, const Vec3& axis);

}  // namespace dfc::dem
