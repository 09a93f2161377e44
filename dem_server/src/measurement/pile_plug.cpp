#include "dfc/dem/pile_plug.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace dfc::dem {

std::vector<PlugTop> plug_tops(const ParticleStore& particles, const CylinderGeometry& tube, double tip_z, std::span<const std::uint8_t> owned) {
  std::vector<PlugTop> tops;
  const double r2_bore = tube.inner_radius * tube.inner_radius;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!owned.empty() && owned[i] == 0) continue;
    const Vec3& x = particles.position[i];
    const double dx = x.x - tube.axis_x, dy = x.y - tube.axis_y;
    const double r = particles.radius[i];
    if (dx * dx + dy * dy < r2_bore && x.z > tip_z) tops.push_back({x.z + r, 4.0 / 3.0 * std::numbers::pi * r * r * r, r});
  }
  return tops;
}

PlugColumn plug_column_of(std::vector<PlugTop> tops, const CylinderGeometry& tube, double tip_z) {
  PlugColumn column;
  column.particles = std::int64_t(tops.size());
  double r_max = 0.0;
  for (const PlugTop& top : tops) r_max = std::max(r_max, top.radius);
  // Highest first; equal tops by volume, so that the order is fixed whatever
  // the particles' order (or the processes that held them).
  std::sort(tops.begin(), tops.end(), [](const PlugTop& a, const PlugTop& b) { return a.z != b.z ? a.z > b.z : a.volume > b.volume; });
  const double loose = plug_loose_fraction * std::numbers::pi * tube.inner_radius * tube.inner_radius * 2.0 * r_max;
  double volume = 0.0;
  for (const PlugTop& top : tops) {
    volume += top.volume;
    if (volume >= loose) {
      column.length = top.z - tip_z;
      break;
    }
  }
  return column;
}

PlugColumn plug_column(const ParticleStore& particles, const CylinderGeometry& tube, double tip_z) {
  return plug_column_of(plug_tops(particles, tube, tip_z), tube, tip_z);
}

}  // namespace dfc::dem
