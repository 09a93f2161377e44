#include "dfc/continuum/tresca_cavity_closed_form.hpp"

#include <cassert>
#include <cmath>

namespace dfc::continuum {

namespace {

bool is_spherical(const TrescaCavity& k) { return k.geometry == CavityGeometry::spherical; }

// Mass balance of the plastic zone (docs/continuum_pile.md §7), in d = 2
// (cylinder) or 3 (sphere) dimensions: with J = (r/c)^β, r^{d−1} dr =
// J r₀^{d−1} dr₀ integrates to (c₀^d − a₀^d)/d = c^β (c^{d−β} − a^{d−β})/(d − β),
// c₀ = c − u(c), u(c) the Lamé displacement at first yield (s_u c/(2G) for the
// cylinder, s_u c/(3G) for the sphere), β = 2s_u/(K + G/3) (cylinder, plane
// strain) or 4s_u/K (sphere). Positive when c is too small.
double mass_balance(const TrescaCavity& k, double a, double c) {
  const bool sphere = is_spherical(k);
  const double d = sphere ? 3.0 : 2.0;
  const double beta = sphere ? 4.0 * k.undrained_strength / k.bulk_modulus
                             : 2.0 * k.undrained_strength / (k.bulk_modulus + k.shear_modulus / 3.0);
  const double c0 = c * (1.0 - k.undrained_strength / (d * k.shear_modulus));
  const double swept = std::pow(c, beta) * (std::pow(c, d - beta) - std::pow(a, d - beta)) / (d - beta);
  return (std::pow(c0, d) - std::pow(k.initial_radius, d)) / d - swept;
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
  const double s = k.undrained_strength;
  const double outer = c / k.outer_radius;
  // σ_r(c): the elastic shell c … b under the pressure σ₀ at b yields at c
  // when the Lamé stress difference reaches 2s_u; then the plastic zone's
  // equilibrium dσ_r/dr + m (σ_r − σ_θ)/r = 0 (m = 1 cylinder, 2 sphere).
  if (is_spherical(k)) return k.in_situ_pressure + 4.0 / 3.0 * s * (1.0 - outer * outer * outer) + 4.0 * s * std::log(c / a);
  return k.in_situ_pressure + s * (1.0 - outer * outer) + 2.0 * s * std::log(c / a);
}

double limit_pressure(const TrescaCavity& k) {
  const double cylinder = k.undrained_strength * (1.0 + std::log(k.shear_modulus / k.undrained_strength));
  return k.in_situ_pressure + (is_spherical(k) ? 4.0 / 3.0 : 1.0) * cylinder;
}

}  // namespace dfc::continuum
