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

enum class LatticeArrangement {
  cubic,  ///< simple cubic: packing fraction pi/6 ~ 0.52 at pitch 2r
  fcc,    ///< face-centred cubic (close-packed layers): pi/(3 sqrt 2) ~ 0.74 at pitch 2r
};

struct LatticeBedSpec {
  BedRegion region;
  LatticeArrangement arrangement = LatticeArrangement::cubic;
  double radius_min = 0.0;      ///< m
  double radius_max = 0.0;      ///< m
  double spacing_factor = 1.05; ///< lattice pitch / (2 radius_max), >= 1
  std::uint64_t seed = 1;
};

struct GeneratedSphere {
  Vec3 centre;
  double radius = 0.0;
};

/// Sites at nearest-neighbour distance a = 2 r_max spacing_factor; each sphere
/// gets a radius uniform in [r_min, r_max] and a random displacement small
/// enough that neighbours never overlap: within +-(a/2 - r) per axis on the
/// cubic lattice (neighbours lie along the axes), and within a ball-bounding
/// +-(a/2 - r)/sqrt 3 per axis on the fcc lattice (neighbours lie diagonally).
/// A denser start (fcc) settles in a fraction of the time a cubic bed takes to
/// collapse. Order: layers in z, then rows in y, then x.
[[nodiscard]] std::vector<GeneratedSphere> generate_lattice_bed(const LatticeBedSpec& spec);

}  // namespace dfc::dem
