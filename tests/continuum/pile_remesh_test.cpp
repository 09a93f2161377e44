// Remeshing the pile problem (docs/continuum_pile.md §5, §6.5): the small
// pile model jacked into the structured Cam clay, held in equilibrium and
// re-triangulated, keeps its force and its mass, and pushed on it follows
// the run that was not remeshed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include <nlohmann/json.hpp>

#include "dfc/continuum/continuum_config.hpp"

namespace dfc::continuum {
namespace {

// tests/e2e/scenarios/open_pile_continuum_small.json's model (0.5 mm
// elements at the wall, 294 triangles, chalk_snw, σ_v = 13.7 kPa, K₀ = 0.6,
// μ = 0.5), built by the server's own reader, without its stop depth.
PileModel small_pile_model() {
  return load_pile_model(nlohmann::json::parse(R"({
    "mesh": {"radius_m": 0.02, "height_m": 0.03, "bore_divisions": 4, "wall_divisions": 2, "outside_divisions": 10,
             "radial_ratio": 1.25, "vertical_divisions": 14, "vertical_ratio": 1.2},
    "material": {"preset": "chalk_snw"},
    "initial_stress": {"vertical_pa": 13700, "k0": 0.6},
    "pile": {"inner_radius_m": 0.003, "outer_radius_m": 0.004, "step_m": 2e-7, "friction": 0.5}})"));
}

constexpr double kStep = 2e-7;  // m per step, the scenario's
// Held, the pile's force settles to 1e-7 of itself and the unbalanced-force
// ratio to 1e-7 in 2000 steps (measured; 1e-12 after 4000).
constexpr int kHoldSteps = 2000;

void push(AxisymmetricSolver& solver, double to_depth) {
  solver.pile().set_velocity(kStep);
  while (solver.pile().penetration() < to_depth - 0.5 * kStep) solver.step();
}

void hold(AxisymmetricSolver& solver) {
  solver.pile().set_velocity(0.0);
  for (int s = 0; s < kHoldSteps; ++s) solver.step();
}

// Jacked 1.5 mm (three wall thicknesses; from about 1.8 mm a triangle under
// the annulus keeps less than 0.6 of its area, the small remeshed scenario's
// trigger) and held. The annulus presses on one node, carried by two thin
// triangles (−34 MPa); the Delaunay triangulation of the same nodes replaces
// them by a fan of five. The transferred states alone (the containing
// triangle plus the recovered difference, §5) left the force −68 % off one
// step later and −40 % settled; −53 % with the plain copy from the containing triangle.
TEST(PileRemesh, AJackedPileInEquilibriumKeepsItsForceAndMassAcrossARemesh) {
  PileModel reference_model = small_pile_model();
  PileModel remeshed_model = small_pile_model();
  AxisymmetricSolver& reference = *reference_model.solver;
  AxisymmetricSolver& solver = *remeshed_model.solver;
  for (AxisymmetricSolver* s : {&reference, &solver}) {
    push(*s, 1.5e-3);
    hold(*s);
  }
  const double force_before = solver.pile_forces().total();
  const double unbalanced_before = solver.unbalanced_force_ratio();
  std::set<Index> pressed;  // the nodes on the pile
  for (Index n = 0; n < solver.pile_contacts().size(); ++n)
    if (solver.pile_contacts()[n].face != PileFace::none) pressed.insert(n);
  std::set<Triangle> old_triangles;
  for (Triangle t : solver.mesh().triangles) {
    std::sort(t.begin(), t.end());
    old_triangles.insert(t);
  }

  const RemeshReport report = solver.remesh();
  Index new_at_the_pile = 0;
  for (Triangle t : solver.mesh().triangles) {
    std::sort(t.begin(), t.end());
    if (!old_triangles.contains(t) && std::any_of(t.begin(), t.end(), [&](Index n) { return pressed.contains(n); })) ++new_at_the_pile;
  }
  solver.step();  // the pile held: its contact on the new mesh
  const double force_at_remesh = solver.pile_forces().total();
  const double unbalanced_at_remesh = solver.unbalanced_force_ratio();
  hold(solver);
  const double force_after = solver.pile_forces().total();
  const double unbalanced_after = solver.unbalanced_force_ratio();
  push(reference, 2e-3);
  push(solver, 2e-3);
  const double reference_force = reference.pile_forces().total();
  const double remeshed_force = solver.pile_forces().total();
  std::printf("pile remesh at 1.5 mm: %zu of %zu triangles new (%zu at the pile's %zu nodes), %d corrections (mismatch %.1e N);\n"
              "  force %.2f N before, %.2f N a step after (%+.4f %%), %.2f N held (%+.4f %%); unbalanced %.1e, %.1e, %.1e;\n"
              "  at 2 mm %.2f N, not remeshed %.2f N (%+.2f %%); mass transferred %+.2e, kept to %.1e\n",
              report.triangles_changed, report.triangles_after, new_at_the_pile, pressed.size(), report.equilibrium_iterations,
              report.equilibrium_residual, force_before, force_at_remesh, 100.0 * (force_at_remesh / force_before - 1.0), force_after,
              100.0 * (force_after / force_before - 1.0), unbalanced_before, unbalanced_at_remesh, unbalanced_after,
              remeshed_force, reference_force, 100.0 * (remeshed_force / reference_force - 1.0),
              (report.mass_transferred - report.mass_before) / report.mass_before, solver.total_mass() / report.mass_before - 1.0);

  // The test means something only if the triangles that carry the pile changed.
  EXPECT_GT(new_at_the_pile, 0u);
  EXPECT_LT(unbalanced_before, 1e-6);
  // The issue's criterion, the force within 1 % across the remesh: a step
  // after it (measured −0.0001 %) and re-equilibrated with the pile held
  // (measured −0.0001 %: the states are in equilibrium and inside their yield
  // surfaces, so nothing moves).
  EXPECT_NEAR(force_at_remesh, force_before, 0.01 * force_before);
  EXPECT_NEAR(force_after, force_before, 0.01 * force_before);
  EXPECT_LT(unbalanced_after, 1e-6);
  // Pushed on to 2 mm the remeshed run follows the one that was not, to the
  // same 1 % (measured +0.4 %: the correction's relaxation has hardened some
  // of the states a little, and the new mesh is a different discretisation).
  EXPECT_NEAR(remeshed_force, reference_force, 0.01 * reference_force);
  // Mass: kept exactly (one scaling factor), and the transferred densities
  // alone within 1 % (the same nodes enclose the same volume).
  EXPECT_NEAR(solver.total_mass(), report.mass_before, 1e-12 * report.mass_before);
  EXPECT_NEAR(report.mass_transferred, report.mass_before, 0.01 * report.mass_before);
}

}  // namespace
}  // namespace dfc::continuum
