// Undrained cylindrical cavity expansion in Modified Cam clay
// (docs/continuum_pile.md §7.1): the solver with the shared structured Cam
// clay model (no structure) and pore water without flow, normally
// consolidated from a₀ to 5a₀ and at OCR 1.5 to 3a₀, against the
// semi-analytical reference of cam_clay_cavity_solution.hpp (the method of
// Collins & Yu 1996 and Cao, Teh & Chang 2001).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

#include "cavity_expansion.hpp"
#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/constitutive/structured_cam_clay_model.hpp"
#include "dfc/continuum/cam_clay_cavity_solution.hpp"

namespace dfc::continuum {
namespace {

// A soft clay: p₀′ = 200 kPa isotropic, no initial excess pore pressure (so
// σ₀ = p₀′), M = 1.2, ρ = v/(λ − κ) = 2/0.16 = 12.5, E′ = 12 MPa, ν′ = 0.3
// (K′ = 10 MPa = v p₀′/κ with v = 2, κ = 0.04; G = 4.6 MPa).
constexpr double kInSitu = 200e3;
constexpr double kSlope = 1.2;
constexpr double kHardening = 12.5;
const constitutive::ElasticModuli kModuli = constitutive::moduli_from_young_poisson(12e6, 0.3);

// Undrained: no flow. The water is softened tenfold so that the test is
// short (as in consolidation_test.cpp): K_f = 220 MPa, n = 0.5, M_w = 440 MPa
// = 95 G. The stiffer the water, the heavier the scaled masses (sized with
// K′ + M_w) and the slower the loading must be; the softer, the further from
// isochoric. The reference is isochoric: the water's compression
// ε_v ≈ Δu/M_w ≈ 9e-4 at the wall raises p′ at the critical state by about
// ρ p′ ε_v ≈ 1 kPa (about 1 % of p′; the hardening takes up the volume
// change), which lowers the excess pore pressure by about 0.3 % and raises
// the cavity pressure a little (with M_w = 1.1 GPa at half the rate, Δu at
// 5a₀ moved by +0.2 % and p by −0.05 %; docs/continuum_pile.md §7.1).
PoreWaterSettings undrained_water() {
  PoreWaterSettings water;
  water.enabled = true;
  water.fluid_bulk_modulus = 2.2e8;
  water.porosity = 0.5;
  water.time_per_step = 0.0;
  return water;
}

// The mesh of the Tresca cylinder (test::cylindrical_test_mesh(): 60 radial
// divisions graded by 1.075 from a₀ = 1 m to b = 100 a₀, the first ring
// 0.1 a₀ wide, one layer 0.1 a₀ high, both faces on rollers: 120
// triangles). At a/a₀ = 5 the wall's ring is 0.021 a₀ wide (aspect ratio 5)
// and keeps 21 % of its area; a radial field needs no remeshing.
const CavityMeshSpec kMesh = test::cylindrical_test_mesh();

CamClayCavity reference_problem(double overconsolidation) {
  return {CavityGeometry::cylindrical, kModuli.shear, kModuli.bulk, kSlope, kHardening, kInSitu, overconsolidation * kInSitu, 0.0,
          kMesh.inner_radius, kMesh.outer_radius};
}

struct ClayRun {
  std::vector<double> radius_ratios;
  std::vector<double> pressures;       ///< total, Pa
  std::vector<double> pore_pressures;  ///< excess, the wall ring's, Pa
  std::vector<double> ring_radii;      ///< m: where the ring's pore pressure is compared
  std::vector<double> unbalanced;
  double smallest_area_ratio = 0.0;
};

// The pore pressure of the ring of triangles at the wall: the volume-weighted
// mean of their nodal means (the p̄_w the solver puts in their total
// stress), at their volume-weighted centroid radius. Not the wall's nodal
// values: at the critical state the nodal field carries a checkerboard of
// ±6 % along the wall's rows (the water's projection is weighted with the
// elastic G, the skeleton's tangent there is nearly zero;
// docs/continuum_pile.md §7.1), which the two triangles of a quadrilateral
// average out.
struct RingPorePressure {
  double pressure = 0.0;
  double radius = 0.0;
};

RingPorePressure wall_ring_pore_pressure(const AxisymmetricSolver& solver) {
  const AxisymmetricMesh& mesh = solver.mesh();
  const std::vector<Index>& wall = mesh.node_group("inner");
  RingPorePressure ring;
  double volume = 0.0;
  for (Index t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    bool at_wall = false;
    for (const Index n : tri) at_wall = at_wall || std::find(wall.begin(), wall.end(), n) != wall.end();
    if (!at_wall) continue;
    const TriangleGeometry g = triangle_geometry(gather(mesh.nodes, tri));
    const double centroid = (mesh.nodes[tri[0]].x() + mesh.nodes[tri[1]].x() + mesh.nodes[tri[2]].x()) / 3.0;
    const double mean = (solver.pore_pressures()[tri[0]] + solver.pore_pressures()[tri[1]] + solver.pore_pressures()[tri[2]]) / 3.0;
    ring.pressure += g.volume() * mean;
    ring.radius += g.volume() * centroid;
    volume += g.volume();
  }
  ring.pressure /= volume;
  ring.radius /= volume;
  return ring;
}

ClayRun expand(double overconsolidation, Index steps, const std::vector<double>& checkpoints) {
  constitutive::StructuredCamClayParameters clay;  // no bonding (p_t = 0), ξ_s = 0: Modified Cam clay
  clay.moduli = kModuli;
  clay.ps0 = overconsolidation * kInSitu;
  clay.mf = kSlope;
  clay.mg = kSlope;
  clay.rho_s = kHardening;
  SolverSettings settings;
  settings.pore_water = undrained_water();
  test::CavityExpansion cavity(test::CavityShape::cylindrical, kMesh, std::make_shared<constitutive::StructuredCamClayModel>(clay), kInSitu,
                               settings);
  ClayRun run;
  std::size_t next = 0;
  cavity.expand_to(checkpoints.back(), steps, [&] {
    if (next < checkpoints.size() && cavity.radius_ratio() >= checkpoints[next] - 1e-12) {
      const RingPorePressure ring = wall_ring_pore_pressure(cavity.solver());
      run.radius_ratios.push_back(cavity.radius_ratio());
      run.pressures.push_back(cavity.wall_pressure());
      run.pore_pressures.push_back(ring.pressure);
      run.ring_radii.push_back(ring.radius);
      run.unbalanced.push_back(cavity.solver().unbalanced_force_ratio());
      ++next;
    }
  });
  run.smallest_area_ratio = cavity.solver().smallest_area_ratio();
  return run;
}

// Asserts at each checkpoint: the cavity pressure (total) and the wall ring's
// excess pore pressure within 2 % of the reference (the tolerance;
// the run's errors are of first order in the loading rate, see the tests),
// and quasi-static motion: an unbalanced-force ratio below 1 %, as for the
// Tresca cavity.
void expect_on_the_reference(double overconsolidation, Index steps, const std::vector<double>& checkpoints) {
  const ClayRun run = expand(overconsolidation, steps, checkpoints);
  const CamClayCavity problem = reference_problem(overconsolidation);
  ASSERT_EQ(run.pressures.size(), checkpoints.size());
  for (std::size_t i = 0; i < run.pressures.size(); ++i) {
    const double a = run.radius_ratios[i] * kMesh.inner_radius;
    const double pressure = cavity_pressure(problem, a);
    const double pore_pressure = excess_pore_pressure(problem, a, run.ring_radii[i]);
    std::printf("OCR %.1f  a/a0 = %.3f  p = %.1f kPa  reference %.1f kPa  error %+.2f %%  u = %.1f kPa  reference %.1f kPa  error %+.2f %%  "
                "unbalanced %.2e\n",
                overconsolidation, run.radius_ratios[i], run.pressures[i] / 1e3, pressure / 1e3, 100.0 * (run.pressures[i] - pressure) / pressure,
                run.pore_pressures[i] / 1e3, pore_pressure / 1e3, 100.0 * (run.pore_pressures[i] - pore_pressure) / pore_pressure, run.unbalanced[i]);
    EXPECT_NEAR(run.pressures[i], pressure, 0.02 * pressure) << "a/a0 = " << run.radius_ratios[i];
    EXPECT_NEAR(run.pore_pressures[i], pore_pressure, 0.02 * pore_pressure) << "a/a0 = " << run.radius_ratios[i];
    EXPECT_LT(run.unbalanced[i], 0.01) << "a/a0 = " << run.radius_ratios[i];
  }
  std::printf("smallest area ratio %.3f, limit pressure (infinite medium) %.1f kPa\n", run.smallest_area_ratio,
              limit_pressure(problem) / 1e3);
}

// Normally consolidated: the whole body yields at once. 300 000 steps to
// 5a₀ (1.3e-5 a₀ per step): at half the rate the pressure errors fall from
// +0.88 / +0.44 / +0.27 / +0.22 % to +0.25 / +0.15 / +0.12 / +0.13 %.
TEST(CamClayCavity, NormallyConsolidatedUndrainedPressureFollowsTheSemiAnalyticalSolutionToFiveTimesTheInitialRadius) {
  expect_on_the_reference(1.0, 300000, {2.0, 3.0, 4.0, 5.0});
}

// Lightly overconsolidated (OCR 1.5, the wet side): elastic to q = M √(p₀′
// (p_c0 − p₀′)), then hardening towards the critical state. Its loading must
// be slower than the normally consolidated one's: at 1.3e-5 a₀ per step the
// errors were +3.0 / +1.4 % at 2a₀ / 3a₀ (unbalanced 1.4e-2), at half that
// rate +1.2 / +0.6 %, first order in the rate. 300 000 steps to 3a₀
// (6.7e-6 a₀ per step, the Tresca cylinder's rate).
TEST(CamClayCavity, LightlyOverconsolidatedUndrainedPressureFollowsTheSemiAnalyticalSolutionToThreeTimesTheInitialRadius) {
  expect_on_the_reference(1.5, 300000, {2.0, 3.0});
}

}  // namespace
}  // namespace dfc::continuum
