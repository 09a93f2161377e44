#pragma once
// Scenario sections shared by the reference-continuum tests.
#include <nlohmann/json.hpp>

namespace dfc::reference::test {

/// The continuum of tests/e2e/scenarios/pile_short.json at 50 g: a cylindrical
/// cavity (interface "inner") in an elastic annulus, bottom fixed, outer wall on
/// radial rollers, geostatic initial stress. Coarser around (8 zones) to stay small.
inline nlohmann::json pile_continuum_section() {
  return nlohmann::json::parse(R"({
    "mesh": {"type": "cylinder_cavity", "inner_radius_m": 0.03, "outer_radius_m": 0.12, "z_bottom_m": 0, "height_m": 0.072,
             "zones_radial": 5, "zones_around": 8, "zones_vertical": 6, "grading_ratio": 1.3},
    "material": {"model": "elastic", "density_kg_m3": 2000, "young_modulus_pa": 5e7, "poisson_ratio": 0.25},
    "gravity_m_s2": [0, 0, -490.5],
    "boundaries": [{"group": "bottom", "condition": "fixed"}, {"group": "outer", "condition": "roller"}],
    "initial_stress": {"type": "geostatic", "k0": 0.5},
    "threads": 1,
    "coupling": {"role": "provider", "group": "inner"}
  })");
}

}  // namespace dfc::reference::test
