#include "dfc/dem/timestep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dfc::dem {

double critical_timestep(const ParticleStore& p, std::span<const StiffnessBound> laws) {
  double kn = 0.0, ks = 0.0;
  for (const auto& law : laws) kn = std::max(kn, law.normal), ks = std::max(ks, law.shear);
  double dt = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double rotation_factor = 1.0 + p.mass[i] * p.radius[i] * p.radius[i] / p.inertia[i];
    const double k = std::max(kn, rotation_factor * ks);
    if (k > 0.0) dt = std::min(dt, std::sqrt(p.mass[i] / k));
  }
  return dt;
}

}  // namespace dfc::dem
