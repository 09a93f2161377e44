#include "dfc/dem/pile_plug.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace dfc::dem {

PlugColumn plug_column(const ParticleStore& particles, const CylinderGeometry& tube, double tip_z) {
  std::vector<double> tops;
  const double r2_bore = tube.inner_radius * tube.inner_radius;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Vec3& x = particles.position[i];
    const double dx = x.x - tube.axis_x, dy = x.y - tube.axis_y;
    if (dx * dx + dy * dy < r2_bore && x.z > tip_z) tops.push_back(x.z + particles.radius[i]);
  }
  PlugColumn column;
  column.particles = std::int64_t(tops.size());
  if (tops.empty()) return column;
  // The k-th highest top, k = the 1 % of the particles from the top (rounded down, at least the highest).
  const auto rank = std::size_t(std::floor((1.0 - plug_top_quantile) * double(tops.size())));
  std::nth_element(tops.begin(), tops.begin() + std::ptrdiff_t(rank), tops.end(), std::greater<>());
  column.length = tops[rank] - tip_z;
  return column;
}

}  // namespace dfc::dem
