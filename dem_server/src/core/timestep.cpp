#include "dfc/dem/timestep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dfc::dem {

StiffnessBound stiffest(StiffnessBound a, const StiffnessBound& b) noexcept {
  a.normal = std::max(a.normal, b.normal);
  a.shear = std::max(a.shear, b.shear);
  return a;
}

double critical_timestep(const ParticleStore& p, const StiffnessBoundAt& bound, StepBound which) {
  double dt = std::numeric_limits<double>::infinity();
  if (p.size() == 0) return dt;
  double r_max = 0.0;
  for (const double r : p.radius) r_max = std::max(r_max, r);
  const StiffnessBound at_largest = bound(r_max);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const StiffnessBound k_i = which == StepBound::per_particle ? bound(p.radius[i]) : at_largest;
    const double rotation_factor = 1.0 + p.mass[i] * p.radius[i] * p.radius[i] / p.inertia[i];
    const double k = std::max(k_i.normal, rotation_factor * k_i.shear);
    if (k > 0.0) dt = std::min(dt, std::sqrt(p.mass[i] / k));
  }
  return dt;
}

}  // namespace dfc::dem
