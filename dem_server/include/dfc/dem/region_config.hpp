#pragma once
// Reading a particle region ({"type":"box"|"cylinder", ...}) and an [x, y]
// pair, shared by the generators ("lattice", "pcrm") and the pile.
#include <array>
#include <string_view>
#include <utility>

#include "dfc/common/config_reader.hpp"
#include "dfc/dem/bed_generator.hpp"

namespace dfc::dem {

/// Reads an [x, y] pair of a declared section (dfc/common/sections/dem_sections.hpp).
[[nodiscard]] std::array<double, 2> read_xy(ConfigReader& cfg, std::string_view key);

/// {"type":"box", "min_m", "max_m"} or {"type":"cylinder", "radius_m", "z_min_m", "z_max_m", "axis_xy_m"}
/// (declared: dem.region); finishes cfg.
[[nodiscard]] BedRegion read_region(ConfigReader cfg);

/// m, the axis-aligned box around a region (lower, upper corner).
[[nodiscard]] std::pair<Vec3, Vec3> region_bounds(const BedRegion& region);

}  // namespace dfc::dem
