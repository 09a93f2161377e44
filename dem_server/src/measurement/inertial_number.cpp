// The inertial number of a loading and the grain scale it needs (inertial_number.hpp).
#include "dfc/dem/inertial_number.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "dfc/dem/exact_sum.hpp"

namespace dfc::dem {

double inertial_number(double shear_rate, double grain_diameter, double pressure, double grain_density) {
  if (!(pressure > 0.0)) return unloaded_inertial_number;
  return std::min(unloaded_inertial_number, shear_rate * grain_diameter / std::sqrt(pressure / grain_density));
}


GrainScale grain_scale(const ParticleStore& particles) {
  const std::size_t n = particles.size();
  if (n == 0) return {};
  const auto [diameter, mass, volume] = exact_sums<3>(n, 1, [&](std::size_t i) {
    const double r = particles.radius[i];
    return std::array<double, 3>{2.0 * r, particles.mass[i], 4.0 / 3.0 * std::numbers::pi * r * r * r};
  });
  return {diameter / double(n), mass / volume};
}

}  // namespace dfc::dem
