#pragma once
// A simple deterministic bed: spheres on a jittered cubic lattice inside a box
// or a vertical cylinder (the DEM region inside the continuum's cavity). No
// two spheres overlap and none crosses the region's boundary; they settle when
// the simulation runs.
#include <cstdint>
#include <vector>

#include "dfc/dem/vec3.hpp"

namespace dfc::dem {

struct BedRegion {
  enum class Shape { box, cylinder };
  Shape shape = Shape::box;
  Vec3 min;               ///< m, box
  Vec3 max;               ///< m, box
  double axis_x = 0.0;    ///< m, cylinder axis (vertical)
  double axis_y = 0.0;
  double radius = 0.0;    ///< m, cylinder
  double z_min = 0.0;     ///< m, cylinder
  double z_max = 0.0;     ///< m, cylinder
};

struct LatticeBedSpec {
  BedRegion region;
  double radius_min = 0.0;      ///< m
  double radius_max = 0.0;      ///< m
  double spacing_factor = 1.05; ///< lattice pitch / (2 radius_max), >= 1
  std::uint64_t seed = 1;
};

struct GeneratedSphere {
  Vec3 centre;
  double radius = 0.0;
};

/// Sites at pitch a = 2 r_max spacing_factor; each sphere gets a radius
/// uniform in [r_min, r_max] and is displaced uniformly within +-(a/2 - r) per
/// axis, so that neighbours (at least a - (a/2 - r_i) - (a/2 - r_j) = r_i + r_j
/// apart) never overlap. Order: layers in z, then rows in y, then x.
[[nodiscard]] std::vector<GeneratedSphere> generate_lattice_bed(const LatticeBedSpec& spec);

}  // namespace dfc::dem
