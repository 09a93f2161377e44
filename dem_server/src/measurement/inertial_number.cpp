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


std::array<double, 4> grain_terms(const ParticleStore& particles, std::size_t i) {
  const double r = particles.radius[i];
  return {1.0, 2.0 * r, particles.mass[i], 4.0 / 3.0 * std::numbers::pi * r * r * r};
}

GrainScale grain_scale_of(const std::array<ExactSum, 4>& sums) {
  const double n = sums[0].value();  // a count below 2^53: exact
  if (n == 0.0) return {};
  return {sums[1].value() / n, sums[2].value() / sums[3].value()};
}

GrainScale grain_scale(const ParticleStore& particles) {
  return grain_scale_of(exact_accumulators<4>(particles.size(), 1, [&](std::size_t i) { return grain_terms(particles, i); }));
}

}  // namespace dfc::dem
