// Coupling verification (docs/theory/coupling.md §5): an elastic box split at a plane into a
// provider and a driven fdm_server, exchanging every step, must converge to the
// static solution of the unsplit box.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "dfc/fdm/fdm_backend.hpp"
#include "fdm_test_support.hpp"

namespace dfc::fdm {
namespace {

using protocol::AdvanceRequest;
using protocol::Array;

nlohmann::json box(double z0, double height, int zones_z, const nlohmann::json& boundaries) {
  nlohmann::json section = nlohmann::json::parse(R"({
    "material": {"model": "elastic", "density_kg_m3": 2000, "young_modulus_pa": 1e7, "poisson_ratio": 0.3},
    "gravity_m_s2": [0, 0, -9.81], "threads": 1})");
  section["mesh"] = {{"type", "box"}, {"origin_m", {0.0, 0.0, z0}}, {"size_m", {1.0, 0.8, height}}, {"zones", {2, 2, zones_z}}};
  section["boundaries"] = boundaries;
  return section;
}

const nlohmann::json kFixedBase = {{{"group", "zmin"}, {"condition", "fixed"}}};
const nlohmann::json kPressedTop = {{{"group", "zmax"}, {"condition", "pressure"}, {"pressure_pa", 5.0e3}}};

Vec3 at(const std::vector<double>& values, std::size_t row) { return {values[3 * row], values[3 * row + 1], values[3 * row + 2]}; }

TEST(SplitBox, ProviderAndDrivenHalvesReproduceTheUnsplitSolution) {
  // Unsplit: base fixed, sides free, pressure on top, gravity — a 3-D field
  // (Poisson bulging) so that the interface carries x, y and z forces.
  nlohmann::json whole = box(0.0, 2.0, 4, kFixedBase);
  whole["boundaries"].push_back(kPressedTop[0]);
  FdmModel reference = load_fdm_model(whole);
  ASSERT_GT(test::run_to_equilibrium(reference.solver, 1.0, 1e-11, 100000), 0);

  nlohmann::json lower = box(0.0, 1.0, 2, kFixedBase);
  lower["coupling"] = {{"role", "provider"}, {"group", "zmax"}};
  nlohmann::json upper = box(1.0, 1.0, 2, kPressedTop);
  upper["coupling"] = {{"role", "driven"}, {"group", "zmin"}};
  FdmBackend provider;
  FdmBackend driven;
  provider.configure(lower);
  driven.configure(upper);
  const protocol::InterfaceMesh interface = provider.interface_mesh();
  driven.set_interface(interface);
  const std::int64_t n = interface.node_count();

  // Serial exchange every step: driven reports its force and mass, the
  // provider steps with them and returns the interface velocity.
  std::vector<double> velocity(std::size_t(3 * n), 0.0);
  std::vector<double> force;
  std::vector<double> mass;
  std::vector<double> interface_displacement;
  int exchanges = 0;
  for (; exchanges < 100000; ++exchanges) {
    const auto d = driven.advance(AdvanceRequest{exchanges, 1, 1.0, {Array::from_f64("velocity", {n, 3}, velocity)}});
    force = protocol::find_array(d.outputs, "force")->to_f64();
    mass = protocol::find_array(d.outputs, "mass")->to_f64();
    const auto p = provider.advance(AdvanceRequest{exchanges, 1, 1.0, {Array::from_f64("force", {n, 3}, force), Array::from_f64("mass", {n}, mass)}});
    velocity = protocol::find_array(p.outputs, "velocity")->to_f64();
    interface_displacement = protocol::find_array(p.outputs, "displacement")->to_f64();
    if (exchanges > 10 && p.monitors["unbalanced_force_ratio"].get<double>() < 1e-11 && d.monitors["unbalanced_force_ratio"].get<double>() < 1e-11)
      break;
  }
  ASSERT_LT(exchanges, 100000) << "the split box did not converge";

  // Compare interface and top displacements with the unsplit gridpoints at the same places.
  const Mesh& mesh = reference.solver.mesh();
  const auto reference_displacement = [&](const Vec3& x) {
    for (std::size_t gp = 0; gp < mesh.points.size(); ++gp)
      if ((mesh.points[gp] - x).norm() < 1e-12) return Vec3(reference.solver.displacements()[gp]);
    ADD_FAILURE() << "no unsplit gridpoint at " << x.transpose();
    return Vec3(Vec3::Zero());
  };
  double scale = 0.0;
  for (const Vec3& u : reference.solver.displacements()) scale = std::max(scale, u.norm());
  double worst = 0.0;
  for (std::size_t r = 0; r < std::size_t(n); ++r)
    worst = std::max(worst, (at(interface_displacement, r) - reference_displacement(at(interface.coordinates, r))).norm() / scale);
  std::string kind;
  const auto snapshot = driven.snapshot(kind);
  const auto positions = protocol::find_array(snapshot, "node_position")->to_f64();
  const auto displacements = protocol::find_array(snapshot, "node_displacement")->to_f64();
  for (std::size_t gp = 0; gp < positions.size() / 3; ++gp)
    worst = std::max(worst, (at(displacements, gp) - reference_displacement(at(positions, gp))).norm() / scale);
  std::printf("[ split box ] %d exchanges; worst displacement difference %.2e of the largest displacement\n", exchanges, worst);
  // Both runs converged to ufr 1e-11; the same discrete static problem then
  // agrees to ~1e-9. 1e-6 still catches any missing force or mass term (O(1)).
  EXPECT_LT(worst, 1e-6);
  // Force balance across the interface: the reaction on the driven body equals the force the provider received, reversed.
  const nlohmann::json pm = provider.monitors();
  const nlohmann::json dm = driven.monitors();
  for (std::size_t c = 0; c < 3; ++c)
    EXPECT_NEAR(pm["interface_force_received"][c].get<double>(), -dm["interface_force_reaction"][c].get<double>(), 1e-9 * 5.0e3);
}

}  // namespace
}  // namespace dfc::fdm
