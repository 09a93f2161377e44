#pragma once
// The inertial number of a loading, I = gamma_dot d / sqrt(p / rho_s) (GDR MiDi
// 2004, eq. 2; da Cruz et al. 2005, eq. 4): the ratio of the time a grain takes
// to rearrange under the pressure p, d / sqrt(p / rho_s), to the time of the
// imposed shear, 1 / gamma_dot. A granular assembly deforms quasi-statically,
// its stresses independent of the rate, for I below about 1e-3 (GDR MiDi 2004,
// section 3). For a pile or foundation pushed at speed v, gamma_dot = v / D
// (D its diameter) and p the tip pressure, tip force over tip area
// (docs/resolution.md section 1): the monitor pile_inertial_number.
#include <array>
#include <cstddef>

#include "dfc/dem/exact_sum.hpp"
#include "dfc/dem/particle_store.hpp"

namespace dfc::dem {

/// I reported where the tip carries no compressive load while the pile moves:
/// the grains there are not held by any pressure, as in a free fall (I -> inf);
/// a finite cap keeps the series a number (the protocol's JSON has no infinity).
inline constexpr double unloaded_inertial_number = 1.0;

/// gamma_dot d / sqrt(p / rho_s), capped at unloaded_inertial_number; that
/// cap where p <= 0. All in SI units.
[[nodiscard]] double inertial_number(double shear_rate, double grain_diameter, double pressure, double grain_density);

struct GrainScale {
  double mean_diameter = 0.0;  ///< m, the particles' mean diameter
  double density = 0.0;        ///< kg/m3, their total mass over their total volume
};

/// The particles' mean diameter and grain density, summed exactly
/// (exact_sum.hpp: the same bits however the particles are ordered or split).
[[nodiscard]] GrainScale grain_scale(const ParticleStore& particles);
/// Slot i's terms of the grain scale's exact sums: 1, 2 r, m, 4/3 pi r^3
/// (a decomposed body sums them over its processes, dem_engine.hpp).
[[nodiscard]] std::array<double, 4> grain_terms(const ParticleStore& particles, std::size_t i);
/// The grain scale from the exact sums of grain_terms over the particles.
[[nodiscard]] GrainScale grain_scale_of(const std::array<ExactSum, 4>& sums);

}  // namespace dfc::dem
