#include "dfc/continuum/local_damping.hpp"

#include <cmath>

namespace dfc::continuum {

namespace {

double sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

}  // namespace

double damped_velocity_change(double force, double velocity, double mass, double damping) {
  return (force - damping * std::abs(force) * sign(velocity)) / mass;
}

double force_for_velocity_change(double change, double velocity, double mass, double damping) {
  return mass * change / (1.0 - damping * sign(velocity) * sign(change));
}

}  // namespace dfc::continuum
