// The continuum with a solid base under its cavity, loaded through its
// provider interface as the DEM core would load it: an elastic body under
// gravity in its geostatic state, the cavity's wall (side and floor) pressed
// by the geostatic stress of the missing material, is in equilibrium.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "dfc/fdm/fdm_backend.hpp"

namespace dfc::fdm {
namespace {

using protocol::Array;

constexpr double kDensity = 1447.0;   // kg/m3, the small generation model's bulk density
constexpr double kGravity = 981.0;    // m/s2, 100 g
constexpr double kK0 = 0.5;
constexpr double kTop = 0.032;        // m
constexpr double kFloor = 0.012;      // m

nlohmann::json section() {
  nlohmann::json s = nlohmann::json::parse(R"({
    "mesh": {"type": "cylinder_cavity", "inner_radius_m": 0.01, "outer_radius_m": 0.05, "height_m": 0.032,
             "cavity_floor_z_m": 0.012, "zones_radial": 6, "zones_around": 16, "zones_vertical": 8, "grading_ratio": 1.3},
    "material": {"model": "elastic", "density_kg_m3": 1447, "young_modulus_pa": 1e9, "poisson_ratio": 0.12},
    "gravity_m_s2": [0, 0, -981],
    "threads": 1,
    "boundaries": [{"group": "bottom", "condition": "fixed"}, {"group": "outer", "condition": "roller"}],
    "initial_stress": {"type": "geostatic", "k0": 0.5},
    "coupling": {"role": "provider", "group": "inner"}
  })");
  return s;
}

/// Geostatic traction sigma n on the cavity's wall (outward normal n, into the
/// cavity): what the missing material would exert. Each triangle's force at its
/// centroid depth goes a third to each corner, as the DEM's wall forces do.
std::vector<double> cavity_loads(const protocol::InterfaceMesh& mesh) {
  std::vector<double> force(mesh.coordinates.size(), 0.0);
  const auto point = [&](std::int64_t r) {
    return Vec3(mesh.coordinates[std::size_t(3 * r)], mesh.coordinates[std::size_t(3 * r + 1)], mesh.coordinates[std::size_t(3 * r + 2)]);
  };
  for (std::size_t f = 0; f < mesh.facets.size(); f += 3) {
    const std::array<std::int64_t, 3> rows = {mesh.facets[f], mesh.facets[f + 1], mesh.facets[f + 2]};
    const Vec3 a = point(rows[0]), b = point(rows[1]), c = point(rows[2]);
    const Vec3 area = 0.5 * (b - a).cross(c - a);  // along the outward normal
    const double sigma_v = kDensity * kGravity * (kTop - (a.z() + b.z() + c.z()) / 3.0);
    const Vec3 traction_times_area = -Vec3(kK0 * sigma_v * area.x(), kK0 * sigma_v * area.y(), sigma_v * area.z());  // compression
    for (const std::int64_t r : rows)
      for (Eigen::Index k = 0; k < 3; ++k) force[std::size_t(3 * r + k)] += traction_times_area[k] / 3.0;
  }
  return force;
}

TEST(CavityFloorGeostatic, TheLoadedCavitysBodyStaysGeostaticAndItsSupportsCarryWeightAndLoad) {
  FdmBackend backend;
  const nlohmann::json info = backend.configure(section());
  const protocol::InterfaceMesh mesh = backend.interface_mesh();
  const std::int64_t n = mesh.node_count();
  const std::vector<double> force = cavity_loads(mesh);
  double applied_z = 0.0;
  for (std::int64_t r = 0; r < n; ++r) applied_z += force[std::size_t(3 * r + 2)];
  // The floor's load is sigma_v at the floor times its (faceted) area: the
  // side's is horizontal, so all of it; 1e-12 is round-off.
  const double floor_load = kDensity * kGravity * (kTop - kFloor) * 0.5 * 16 * 0.01 * 0.01 * std::sin(2.0 * 3.141592653589793 / 16);
  EXPECT_NEAR(-applied_z, floor_load, 1e-12 * floor_load);

  const double dt = info["dt_suggested"].get<double>();
  nlohmann::json monitors;
  std::vector<double> velocity;
  int exchanges = 0;
  for (; exchanges < 400; ++exchanges) {
    const auto result = backend.advance({0, 50, dt, {Array::from_f64("force", {n, 3}, force)}});
    monitors = result.monitors;
    velocity = protocol::find_array(result.outputs, "velocity")->to_f64();
    if (exchanges > 2 && monitors["unbalanced_force_ratio"].get<double>() < 1e-6) break;
  }
  ASSERT_LT(monitors["unbalanced_force_ratio"].get<double>(), 1e-6) << "after " << exchanges << " exchanges";
  EXPECT_EQ(velocity.size(), std::size_t(3 * n));

  // Weight balance: the supports (fixed bottom, outer roller) carry the grid's
  // weight and the floor's load. The rest is the unbalanced force, below 1e-6
  // of the mean gridpoint force, so 1e-5 is a safe margin.
  const double weight = monitors["total_weight_n"].get<double>();
  const double support = monitors["support_reaction_n"][2].get<double>();
  std::cout << "weight " << weight << " N + floor load " << floor_load << " N = supports " << support << " N ("
            << 100.0 * (support / (weight + floor_load) - 1.0) << " %) after " << exchanges << " exchanges\n";
  EXPECT_NEAR(support, weight + floor_load, 1e-5 * (weight + floor_load));

  // The geostatic state is nearly the discrete equilibrium: the zone stresses
  // move little from it (measured: sigma_v by 1.1 % and sigma_h by 0.6 % of the
  // local sigma_v at worst, the displacements 0.35 % of the self-weight scale);
  // the lumped corner loads of the non-rectangular floor faces and the
  // triangle-centroid depths of the side loads differ slightly from the zones'
  // own nodal forces. (A floor left out of the coupling group fails the
  // balance above: its load is 2.5 % of the total.)
  std::string kind;
  const auto snapshot = backend.snapshot(kind);
  const auto nodes = protocol::find_array(snapshot, "node_position")->to_f64();
  const auto zones = protocol::find_array(snapshot, "zone_nodes")->to_i64();
  const auto stress = protocol::find_array(snapshot, "zone_stress")->to_f64();  // xx, xy, xz, yy, yz, zz
  const auto displacement = protocol::find_array(snapshot, "node_displacement")->to_f64();
  double worst_v = 0.0, worst_h = 0.0, worst_u = 0.0;
  for (std::size_t z = 0; z < zones.size() / 8; ++z) {
    double centroid = 0.0;
    for (std::size_t k = 0; k < 8; ++k) centroid += nodes[3 * std::size_t(zones[8 * z + k]) + 2] / 8.0;
    const double sigma_v = kDensity * kGravity * (kTop - centroid);
    worst_v = std::max(worst_v, std::abs(-stress[6 * z + 5] - sigma_v) / sigma_v);
    worst_h = std::max(worst_h, std::abs(-0.5 * (stress[6 * z] + stress[6 * z + 3]) - kK0 * sigma_v) / sigma_v);
  }
  for (const double u : displacement) worst_u = std::max(worst_u, std::abs(u));
  // Scale of the self-weight displacements: sigma_v at the bottom over E, times the height.
  const double scale = kDensity * kGravity * kTop / 1e9 * kTop;
  std::cout << "worst |d sigma_v| / sigma_v " << worst_v << ", |d sigma_h| / sigma_v " << worst_h << ", |u| " << worst_u << " m (scale " << scale
            << " m)\n";
  EXPECT_LT(worst_v, 0.02);
  EXPECT_LT(worst_h, 0.01);
  EXPECT_LT(worst_u, 0.01 * scale);
}

}  // namespace
}  // namespace dfc::fdm
