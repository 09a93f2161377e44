// The Dohrmann–Bochev pressure projection (docs/continuum_pile.md §3): the
// properties its use rests on, on a small distorted mesh, and the
// incompressible patch test of the solver with it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <vector>

#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/continuum/axisymmetric_solver.hpp"
#include "dfc/continuum/cavity_meshes.hpp"
#include "dfc/continuum/nodal_average.hpp"
#include "dfc/continuum/pressure_projection.hpp"

namespace dfc::continuum {
namespace {

/// A block 1 ≤ r ≤ 2, 0 ≤ z ≤ 1 of 6 × 6 quadrilaterals (72 triangles), its
/// interior nodes moved by up to 0.15 of the spacing in a fixed pseudo-random
/// pattern: no two triangles alike.
AxisymmetricMesh distorted_block() {
  AxisymmetricMesh mesh = strip_mesh(
      {.inner_radius = 1.0, .outer_radius = 2.0, .radial_divisions = 6, .radial_ratio = 1.0, .tangential_divisions = 6, .strip_height = 1.0});
  std::vector<bool> on_boundary(mesh.nodes.size(), false);
  for (const auto& [name, group] : mesh.node_groups)
    for (const Index n : group) on_boundary[n] = true;
  const double spacing = 1.0 / 6.0;
  for (Index n = 0; n < mesh.nodes.size(); ++n) {
    if (on_boundary[n]) continue;
    const double k = static_cast<double>(n);
    mesh.nodes[n] += 0.15 * spacing * Point(std::sin(7.0 * k), std::cos(5.0 * k));
  }
  return mesh;
}

std::vector<double> volumes_of(const AxisymmetricMesh& mesh) {
  std::vector<double> volumes;
  for (const Triangle& t : mesh.triangles) volumes.push_back(triangle_geometry(gather(mesh.nodes, t)).volume());
  return volumes;
}

/// Triangle values that vary from one triangle to the next (a checkerboard on a smooth trend).
std::vector<double> rough_values(Index count) {
  std::vector<double> values;
  for (Index t = 0; t < count; ++t) values.push_back(1e-4 * (1.0 + 0.01 * double(t) + ((t % 2 == 0) ? 0.5 : -0.5)));
  return values;
}

// τ = K/G at ν = 0.4999.
constexpr double kWeight = 5000.0;

TEST(PressureProjection, UniformTriangleValuesGiveTheSameUniformNodalField) {
  const AxisymmetricMesh mesh = distorted_block();
  const std::vector<double> volumes = volumes_of(mesh);
  const std::vector<double> uniform(mesh.triangles.size(), 3e-4);
  PressureProjection projection;
  for (const double value : projection.nodal_solution(mesh.triangles, mesh.nodes.size(), volumes, kWeight, uniform))
    EXPECT_NEAR(value, 3e-4, 1e-14);  // S annihilates a uniform field; round-off of a system with entries 5000 × the mass
}

TEST(PressureProjection, WithoutTheStabilisationItIsTheNodalAverage) {
  const AxisymmetricMesh mesh = distorted_block();
  const std::vector<double> volumes = volumes_of(mesh);
  const std::vector<double> values = rough_values(mesh.triangles.size());
  PressureProjection projection;
  const std::vector<double> projected = projection.nodal_solution(mesh.triangles, mesh.nodes.size(), volumes, 0.0, values);
  const std::vector<double> averaged = nodal_means(mesh.triangles, mesh.nodes.size(), volumes, values);
  for (Index n = 0; n < projected.size(); ++n) EXPECT_NEAR(projected[n], averaged[n], 1e-15);
}

TEST(PressureProjection, ConservesTheVolumeChangeAndSmoothsACheckerboard) {
  const AxisymmetricMesh mesh = distorted_block();
  const std::vector<double> volumes = volumes_of(mesh);
  const std::vector<double> values = rough_values(mesh.triangles.size());
  PressureProjection projection;
  const std::vector<double> projected = projection.nodal_solution(mesh.triangles, mesh.nodes.size(), volumes, kWeight, values);
  // Σ_n M_n e_n = Σ_e V_e v_e, M_n = Σ_e V_e/3: S's rows sum to zero.
  double nodal_volume_change = 0.0;
  for (Index t = 0; t < mesh.triangles.size(); ++t)
    for (const Index n : mesh.triangles[t]) nodal_volume_change += volumes[t] / 3.0 * projected[n];
  const double volume_change = std::inner_product(volumes.begin(), volumes.end(), values.begin(), 0.0);
  EXPECT_NEAR(nodal_volume_change, volume_change, 1e-12 * std::abs(volume_change));
  // The ±50 % checkerboard of the input: the projected triangle values
  // (means of their nodes) keep much less of it than the plain nodal average.
  const auto spread = [&](const std::vector<double>& triangle_values) {
    double largest = 0.0;
    for (Index t = 0; t + 1 < triangle_values.size(); ++t)
      largest = std::max(largest, std::abs(triangle_values[t + 1] - triangle_values[t]));
    return largest;
  };
  const double projected_spread = spread(triangle_means(mesh.triangles, projected));
  const double averaged_spread = spread(nodal_average(mesh.triangles, mesh.nodes.size(), volumes, values));
  std::printf("neighbour-to-neighbour spread: %.2e projected, %.2e averaged, %.2e given\n", projected_spread, averaged_spread, 1e-4);
  EXPECT_LT(projected_spread, 0.5 * averaged_spread);
}

TEST(PressureProjection, AnOldFactorisationPreconditionsAMovedGeometryToTheSameSolution) {
  const AxisymmetricMesh mesh = distorted_block();
  std::vector<double> volumes = volumes_of(mesh);
  const std::vector<double> values = rough_values(mesh.triangles.size());
  PressureProjection reused;
  (void)reused.nodal_solution(mesh.triangles, mesh.nodes.size(), volumes, kWeight, values);
  for (Index t = 0; t < volumes.size(); ++t) volumes[t] *= 1.0 + 0.01 * std::sin(double(t));  // 1 % changes, as of many steps
  const std::vector<double> iterated = reused.nodal_solution(mesh.triangles, mesh.nodes.size(), volumes, kWeight, values);
  PressureProjection fresh;
  const std::vector<double> direct = fresh.nodal_solution(mesh.triangles, mesh.nodes.size(), volumes, kWeight, values);
  EXPECT_GT(reused.last_iterations(), 0);
  EXPECT_LE(reused.last_iterations(), 4);
  for (Index n = 0; n < direct.size(); ++n) EXPECT_NEAR(iterated[n], direct[n], 1e-9 * std::abs(direct[n]));
}

TEST(PressureProjection, HeldNodesKeepAZeroChange) {
  const AxisymmetricMesh mesh = distorted_block();
  const std::vector<double> volumes = volumes_of(mesh);
  std::vector<bool> held(mesh.nodes.size(), false);
  for (const Index n : mesh.node_group("top")) held[n] = true;
  const std::vector<double> rhs(mesh.nodes.size(), 1.0);
  PressureProjection projection;
  const std::vector<double> solution = projection.solve(mesh.triangles, volumes, {1e-8, 1e-6}, held, rhs);
  for (Index n = 0; n < solution.size(); ++n) {
    if (held[n]) EXPECT_EQ(solution[n], 0.0);
    else EXPECT_GT(solution[n], 0.0);
  }
}

// The incompressible patch test: the distorted block at ν = 0.4999,
// compressed along z by ε = 1e-4 between a base on rollers and a moved top,
// its sides free. The exact solution is uniform uniaxial stress
// σ_zz = E ln(1 − ε), σ_rr = σ_θθ = σ_rz = 0 (a linear displacement field,
// which linear triangles represent exactly), so every triangle must carry it,
// and the pressure must be uniform: a scheme that is not consistent
// (or carries a spurious pressure mode) fails on a distorted mesh.
TEST(PressureProjection, NearlyIncompressiblePatchTestGivesAUniformStress) {
  const double young = 1e7;
  const constitutive::ElasticModuli moduli = constitutive::moduli_from_young_poisson(young, 0.4999);
  AxisymmetricSolver solver(distorted_block(), std::make_shared<constitutive::ElasticModel>(moduli), Stress{});
  solver.prescribe_velocity(solver.mesh().node_group("bottom"), Axis::z, 0.0);
  const double strain = 1e-4;
  const Index steps = 5000;
  solver.prescribe_velocity(solver.mesh().node_group("top"), Axis::z, -strain / double(steps));
  for (Index s = 0; s < steps; ++s) solver.step();
  solver.prescribe_velocity(solver.mesh().node_group("top"), Axis::z, 0.0);
  for (Index s = 0; s < 60000; ++s) solver.step();  // K/G = 5000: the shear modes settle slowly
  const double expected = young * std::log(1.0 - strain);
  double worst_axial = 0.0, worst_lateral = 0.0;
  for (const Stress& stress : solver.stresses()) {
    worst_axial = std::max(worst_axial, std::abs(stress.zz - expected));
    worst_lateral = std::max({worst_lateral, std::abs(stress.xx), std::abs(stress.yy), std::abs(stress.zx)});
  }
  std::printf("patch test: max |s_zz - E ln(1 - eps)| = %.2e Pa, max lateral/shear stress %.2e Pa, of |s_zz| = %.3e Pa\n",
              worst_axial, worst_lateral, std::abs(expected));
  // Measured 4.7e-7 of the stress, the same after 200 000 steps: round-off
  // of the increments, whose volumetric part is amplified K/G = 5000 times in
  // the pressure. 1e-5: a checkerboard or an inconsistent stabilisation
  // would be of the order of the stress itself.
  EXPECT_LT(worst_axial, 1e-5 * std::abs(expected));
  EXPECT_LT(worst_lateral, 1e-5 * std::abs(expected));
}

}  // namespace
}  // namespace dfc::continuum
