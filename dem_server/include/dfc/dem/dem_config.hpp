#pragma once
// The DEM section of a scenario: schema, validation and defaults.
// The full key list with units and defaults is dem_config_help() (--help of
// dem_server); errors are dfc::ConfigError with the key path inside the section.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dfc/dem/bed_generator.hpp"
#include "dfc/dem/contact_law_registry.hpp"
#include "dfc/dem/equilibrium_target.hpp"
#include "dfc/dem/periodic_config.hpp"
#include "dfc/dem/radius_expansion.hpp"
#include "dfc/dem/triaxial_walls.hpp"
#include "dfc/dem/wall.hpp"
#include "dfc/dem/wall_builders.hpp"

namespace dfc::dem {

struct ParticleConfig {
  std::string generator;                ///< "lattice", "list" or "radius_expansion"
  LatticeBedSpec lattice;               ///< generator "lattice"
  RadiusExpansionSpec expansion;        ///< generator "radius_expansion" (spheres at the start radii)
  std::vector<double> final_radius;     ///< m, generator "radius_expansion": by id
  double density = 0.0;                 ///< kg/m3
  std::vector<GeneratedSphere> spheres; ///< generated or listed; id = index
};

struct WallConfig {
  std::string name;
  WallMesh mesh;
  Vec3 velocity;  ///< m/s
  std::int64_t start_step = 0;
  ContactLawSetting contact;
};

struct PileConfig {
  CylinderGeometry geometry;
  Vec3 velocity;  ///< m/s
  std::int64_t start_step = 0;
  ContactLawSetting contact;
};

/// Uniaxial compression between two of the walls (docs/dem_ucs.md, ucs_platens.hpp).
struct UcsConfig {
  std::size_t top_wall = 0;     ///< index into DemConfig::walls
  std::size_t bottom_wall = 0;  ///< index into DemConfig::walls
  double area = 0.0;            ///< m2, sample cross-section (given, or derived from the particles)
  std::optional<double> strain_rate;  ///< 1/s; when given, the platens were set moving at ±rate H0/2
  std::int64_t start_step = 0;        ///< first step of the platens' motion when strain_rate is given
};

/// Triaxial compression in six rigid walls (docs/dem_triaxial_walls.md, triaxial_walls.hpp):
/// confinement of every wall to sigma_3 (preparation), bonds, then the platens
/// close at the strain rate while the lateral walls hold sigma_3.
struct TriaxialConfig {
  TriaxialWalls walls;              ///< indices into DemConfig::walls (the simulation adds them first, in order)
  double confining_stress = 0.0;    ///< Pa, sigma_3
  double strain_rate = 0.0;         ///< 1/s, axial, compression positive
  double servo_gain = 0.5;
  std::optional<double> max_strain_rate;  ///< 1/s, cap of a servo-controlled wall pair; default 1e-4 / dt
  EquilibriumTarget confinement;    ///< when the confinement stage is finished
};

struct TimestepConfig {
  double fraction_of_critical = 0.2;
  std::optional<double> dt;  ///< s, fixed step instead of a fraction
};

struct DemConfig {
  double scale_factor = 1.0;       ///< particle upscaling S (radii and law parameters already scaled)
  ParticleConfig particles;
  ContactLawSetting contact;       ///< particle–particle
  ContactLawSetting wall_contact;  ///< particle–wall default, and the coupling wall
  double local_damping = 0.7;
  TimestepConfig timestep;
  Vec3 gravity;                    ///< m/s^2
  double skin = 0.0;               ///< m; 0: automatic (0.2 r_max)
  std::vector<WallConfig> walls;
  std::optional<PileConfig> pile;
  std::optional<UcsConfig> ucs;
  std::optional<TriaxialConfig> triaxial;
  std::optional<PeriodicConfig> periodic;
  int threads = 0;
};

/// Validates the whole section (unknown keys are errors). Generates the bed.
[[nodiscard]] DemConfig parse_dem_config(const nlohmann::json& section);

/// The schema in words, with the contact-law registry (for --help).
[[nodiscard]] std::string dem_config_help();

}  // namespace dfc::dem
