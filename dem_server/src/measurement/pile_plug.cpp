#include "dfc/dem/pile_plug.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace dfc::dem {

PlugColumn plug_column(const ParticleStore& particles, const CylinderGeometry& tube, double tip_z) {
  std::vector<double> tops;
  double r_max = 0.0;
  const double r2_bore = tube.inner_radius * tube.inner_radius;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Vec3& x = particles.position[i];
    const double dx = x.x - tube.axis_x, dy = x.y - tube.axis_y;
    if (dx * dx + dy * dy < r2_bore && x.z > tip_z) {
      tops.push_back(x.z + particles.radius[i]);
      r_max = std::max(r_max, particles.radius[i]);
    }
  }
  PlugColumn column;
  column.particles = std::int64_t(tops.size());
  if (tops.empty()) return column;
  std::sort(tops.begin(), tops.end(), std::greater<>());
  std::size_t k = 0;
  while (k + 1 < tops.size() && tops[k] - tops[k + 1] > 2.0 * r_max) ++k;  // skip the loose ones above the column
  column.length = tops[k] - tip_z;
  return column;
}

}  // namespace dfc::dem
