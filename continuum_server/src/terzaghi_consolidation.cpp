#include "dfc/continuum/terzaghi_consolidation.hpp"

#include <cmath>
#include <numbers>

namespace dfc::continuum {

namespace {

/// Σ_m term(M) until the exponential factor no longer matters (it decays
/// like exp(−M² T); for T → 0 the sine series needs many terms, capped).
template <typename Term>
double series(double time_factor, Term&& term) {
  double sum = 0.0;
  for (int m = 0; m < 200000; ++m) {
    const double big_m = (2.0 * m + 1.0) * std::numbers::pi / 2.0;
    const double decay = std::exp(-big_m * big_m * time_factor);
    if (decay < 1e-17 && m > 0) break;
    sum += term(big_m, decay);
  }
  return sum;
}

}  // namespace

double terzaghi_pressure_ratio(double depth_ratio, double time_factor) {
  return series(time_factor, [&](double big_m, double decay) { return 2.0 / big_m * std::sin(big_m * depth_ratio) * decay; });
}

double terzaghi_degree_of_consolidation(double time_factor) {
  return 1.0 - series(time_factor, [](double big_m, double decay) { return 2.0 / (big_m * big_m) * decay; });
}

double OedometricBiotColumn::undrained_pore_pressure(double load) const {
  return biot_coefficient * load * biot_modulus / (constrained_modulus + biot_coefficient * biot_coefficient * biot_modulus);
}

double OedometricBiotColumn::consolidation_coefficient() const {
  return mobility / (1.0 / biot_modulus + biot_coefficient * biot_coefficient / constrained_modulus);
}

}  // namespace dfc::continuum
