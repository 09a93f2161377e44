#include "dfc/dem/pile_plug.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace dfc::dem {

PlugColumn plug_column(const ParticleStore& particles, const CylinderGeometry& tube, double tip_z) {
  struct Top {
    double z;       ///< m, z + r
    double volume;  ///< m3
  };
  std::vector<Top> tops;
  double r_max = 0.0;
  const double r2_bore = tube.inner_radius * tube.inner_radius;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Vec3& x = particles.position[i];
    const double dx = x.x - tube.axis_x, dy = x.y - tube.axis_y;
    const double r = particles.radius[i];
    if (dx * dx + dy * dy < r2_bore && x.z > tip_z) {
      tops.push_back({x.z + r, 4.0 / 3.0 * std::numbers::pi * r * r * r});
      r_max = std::max(r_max, r);
    }
  }
  PlugColumn column;
  column.particles = std::int64_t(tops.size());
  // Highest first; equal tops by volume, so that the order is fixed whatever the particles' order.
  std::sort(tops.begin(), tops.end(), [](const Top& a, const Top& b) { return a.z != b.z ? a.z > b.z : a.volume > b.volume; });
  const double loose = plug_loose_fraction * std::numbers::pi * r2_bore * 2.0 * r_max;
  double volume = 0.0;
  for (const Top& top : tops) {
    volume += top.volume;
    if (volume >= loose) {
      column.length = top.z - tip_z;
      break;
    }
  }
  return column;
}

}  // namespace dfc::dem
