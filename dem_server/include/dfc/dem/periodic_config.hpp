#pragma once
// The "periodic" block of the DEM section and the "radius_expansion"
// particle generator (docs/dem_periodic.md §6). Kept apart from dem_config.cpp
// so that the REV keys (and, later, upscaling of them) merge without conflicts.
#include <cstdint>
#include <optional>
#include <string>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/sections/dem_sections.hpp"
#include "dfc/dem/cell_servo.hpp"
#include "dfc/dem/equilibrium_target.hpp"
#include "dfc/dem/periodic_cell.hpp"
#include "dfc/dem/radius_expansion.hpp"

namespace dfc::dem {

/// How the cell is driven: during preparation ("consolidation") and during the
/// coupled advance ("loading").
struct CellLoading {
  enum class Mode { none, isotropic, k0, anisotropic, triaxial, strain_rate };
  Mode mode = Mode::none;
  std::size_t axis = 2;     ///< k0 / anisotropic / triaxial: the vertical or axial edge (0 x, 1 y, 2 z)
  double stress = 0.0;      ///< Pa, compression positive: p (isotropic), sigma_v (k0, anisotropic), sigma_3 (triaxial)
  double lateral_ratio = 1.0;  ///< -, anisotropic: sigma_h / sigma_v held on the two other edges (a K0 state)
  double axial_rate = 0.0;  ///< 1/s, triaxial: axial strain rate, > 0 compresses, < 0 pulls (direct tension)
  Vec3 strain_rate;         ///< 1/s, strain_rate mode: edge rates, extension positive
};

/// The stopping rule (tolerance, unbalanced force ratio, steps) and the loading.
struct ConsolidationSpec : EquilibriumTarget {
  CellLoading loading;  ///< isotropic or k0
};

struct PeriodicConfig {
  PeriodicCell cell;
  double servo_gain = sections::kDefaultServoGain;
  std::optional<double> max_strain_rate;      ///< 1/s; default 1e-4 / dt (set by the model builder)
  std::optional<ConsolidationSpec> consolidation;
  CellLoading loading;
};

/// Reads "periodic": min_m, max_m, axes, servo, consolidation, loading.
[[nodiscard]] PeriodicConfig read_periodic_config(ConfigReader cfg);

/// Reads a "servo" block ({"gain", "max_strain_rate_per_s"}) into `config` and finishes it.
void read_servo(ConfigReader servo, PeriodicConfig& config);

/// Reads the keys of generator "radius_expansion" inside "particles" (not
/// density or generator, which the caller reads).
[[nodiscard]] RadiusExpansionSpec read_radius_expansion(ConfigReader& particles);

/// Fails on "<periodic>.min_m" if a periodic edge is shorter than 2 (2 r_max + reach),
/// with reach the larger of the skin and the bond gap.
void check_periodic_width(const PeriodicConfig& config, double r_max, double reach, const std::string& path);

/// The servo that realises a loading (none: every edge fixed).
[[nodiscard]] CellServo make_servo(const CellLoading& loading, double gain, double max_strain_rate);


}  // namespace dfc::dem
