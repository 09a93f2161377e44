#include "dfc/continuum/tresca_cavity_closed_form.hpp"

#include <cassert>
#include <cmath>

namespace dfc::continuum {

namespace {

// Mass balance of the plastic ring (docs/continuum_pile.md §7): with
// J = (r/c)^β, β = 2s_u/(K + G/3), r dr = J r₀ dr₀ integrates to
// c₀² − a₀² = 2c^β (c^{2−β} − a^{2−β})/(2 − β), c₀ = c − u(c), u(c) = s_u c/(2G)
// (the Lamé displacement at first yield). Positive when c is too small.
double mass_balance(const TrescaCavity& k, double a, double c) {
  const double beta = 2.0 * k.undrained_strength / (k.bulk_modulus + k.shear_modulus / 3.0);
  const double c0 = c * (1.0 - k.undrained_strength / (2.0 * k.shear_modulus));
  const double swept = 2.0 * std::pow(c, beta) * (std::pow(c, 2.0 - beta) - std::pow(a, 2.0 - beta)) / (2.0 - beta);
  return c0 * c0 - k.initial_radius * k.initial_radius - swept;
}

}  // namespace

double plastic_radius(const TrescaCavity& k, double a) {
  double low = a;  // c ≥ a
  double high = a;
  while (mass_balance(k, a, high) > 0.0) high *= 2.0;
  assert(mass_balance(k, a, low) > 0.0 && "the cavity has not yielded yet");
  for (int i = 0; i < 200 && high - low > 1e-14 * high; ++i) {
    const double mid = 0.5 * (low + high);
    (mass_balance(k, a, mid) > 0.0 ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

double cavity_pressure(const TrescaCavity& k, double a) {
  const double c = plastic_radius(k, a);
  // σ_r(c) = σ₀ + s_u (1 − c²/b²): the elastic annulus c … b under the pressure
  // σ₀ at b yields at c when the Lamé stress difference reaches 2s_u.
  const double at_plastic_boundary = k.undrained_strength * (1.0 - (c * c) / (k.outer_radius * k.outer_radius));
  return k.in_situ_pressure + at_plastic_boundary + 2.0 * k.undrained_strength * std::log(c / a);
}

double limit_pressure(const TrescaCavity& k) {
  return k.in_situ_pressure + k.undrained_strength * (1.0 + std::log(k.shear_modulus / k.undrained_strength));
}

}  // namespace dfc::continuum
