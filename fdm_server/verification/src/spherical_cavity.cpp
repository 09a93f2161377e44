// Spherical cavity on an octant of a spherical shell (symmetry rollers on the
// coordinate planes), Mohr–Coulomb material. From the isotropic in-situ state,
// the cavity pressure is ramped to p_e = p0 + 0.9 (p_y − p0) with the
// closed-form σ_r(b) on the outer boundary (so the shell has the infinite
// medium's solution). The elastic field is checked on shell averages.
//
// First yield of the discrete model: below first yield the response is linear
// in p − p0, so the pressure at which the wall reaches the yield surface
// follows from the computed wall stresses at p_e. The wall stresses are the
// two innermost shells extrapolated with the general spherically symmetric
// elastic field σ = A + B/r³ (not the closed form's coefficients).
#include "dfc/fdm/verification/spherical_cavity.hpp"

#include <cmath>
#include <memory>
#include <numbers>

#include "dfc/fdm/mesh_generators.hpp"
#include "dfc/constitutive/mohr_coulomb_model.hpp"
#include "dfc/fdm/verification/fixtures.hpp"

namespace dfc::fdm::verification {

namespace {

constexpr double kOuterRadius = 5.0;  // in radii
constexpr double kLoadFraction = 0.9; // of the way from p0 to p_y
constexpr int kRampSteps = 2000;

// A + B/r³ through two points, evaluated at r.
double extrapolate_cubic_decay(double r, double r1, double y1, double r2, double y2) {
  return extrapolate_linear(1.0 / (r * r * r), 1.0 / (r1 * r1 * r1), y1, 1.0 / (r2 * r2 * r2), y2);
}

}  // namespace

double SphericalCavitySolution::kp() const {
  const double s = std::sin(friction_deg * std::numbers::pi / 180.0);
  return (1.0 + s) / (1.0 - s);
}

double SphericalCavitySolution::first_yield_pressure() const {
  const double y = 2.0 * cohesion * std::sqrt(kp());
  return in_situ + 2.0 * ((kp() - 1.0) * in_situ + y) / (kp() + 2.0);
}

double SphericalCavitySolution::radial_stress(double r, double pressure) const { return in_situ + (pressure - in_situ) * std::pow(radius / r, 3); }

double SphericalCavitySolution::hoop_stress(double r, double pressure) const {
  return in_situ - 0.5 * (pressure - in_situ) * std::pow(radius / r, 3);
}

double SphericalCavitySolution::radial_displacement(double r, double pressure) const {
  return (pressure - in_situ) * std::pow(radius, 3) / (4.0 * shear_modulus() * r * r);
}

ProblemResult run_spherical_cavity(int level) {
  const Stopwatch clock;
  const SphericalCavitySolution s;
  const Index nr = 12 * (Index(1) << level);
  const Index n = 6 * (Index(1) << level);
  SphereCavityOctantSpec spec;
  spec.inner_radius = s.radius;
  spec.outer_radius = kOuterRadius * s.radius;
  spec.zones_radial = nr;
  spec.zones_around = n;
  spec.grading_ratio = std::pow(kOuterRadius, 1.0 / double(nr));  // Δr ∝ r: near-cubic zones at every radius
  const constitutive::MohrCoulombStrength strength{s.cohesion, s.friction_deg, 0.0, 0.0};
  auto model = std::make_unique<constitutive::MohrCoulombModel>(constitutive::moduli_from_young_poisson(s.young_modulus, s.poisson_ratio), strength);
  Solver solver(make_sphere_cavity_octant(spec), Material{2000.0, std::move(model)}, static_settings());
  for (const char* plane : {"xmin", "ymin", "zmin"}) solver.apply_boundary_condition({plane, BoundaryKind::roller});
  solver.set_initial_stress([&](const Vec3&) { return SymTensor::isotropic(-s.in_situ); });

  const double pressure = s.in_situ + kLoadFraction * (s.first_yield_pressure() - s.in_situ);
  const Mesh& mesh = solver.mesh();
  const std::vector<Vec3> inner_from = pressure_forces(mesh, "inner", s.in_situ);
  const std::vector<Vec3> inner_to = pressure_forces(mesh, "inner", pressure);
  const std::vector<Vec3> outer_from = pressure_forces(mesh, "outer", s.in_situ);
  const std::vector<Vec3> outer_to = pressure_forces(mesh, "outer", s.radial_stress(spec.outer_radius, pressure));
  std::vector<Vec3> from(mesh.gridpoint_count()), to(mesh.gridpoint_count());
  for (std::size_t gp = 0; gp < from.size(); ++gp) {
    from[gp] = inner_from[gp] + outer_from[gp];
    to[gp] = inner_to[gp] + outer_to[gp];
  }
  ramp_external_forces(solver, from, to, kRampSteps);
  ProblemResult result;
  result.steps = kRampSteps + equilibrate(solver, "spherical cavity");

  const std::vector<LayerStress> shells = radial_layers(solver, nr, true);
  const LayerStress* probe = &shells.front();  // the shell nearest r = 1.5a
  for (const LayerStress& shell : shells)
    if (std::abs(shell.radius - 1.5 * s.radius) < std::abs(probe->radius - 1.5 * s.radius)) probe = &shell;
  // Wall stresses (compression positive) and the load factor at which they reach
  // σ_r = K_p σ_θ + Y along the linear path from p0.
  const double wall_r = -extrapolate_cubic_decay(s.radius, shells[0].radius, shells[0].rr, shells[1].radius, shells[1].rr);
  const double wall_t = -extrapolate_cubic_decay(s.radius, shells[0].radius, shells[0].tt, shells[1].radius, shells[1].tt);
  const double y = 2.0 * s.cohesion * std::sqrt(s.kp());
  const double factor = ((s.kp() - 1.0) * s.in_situ + y) / ((wall_r - s.in_situ) - s.kp() * (wall_t - s.in_situ));
  const double computed_yield = s.in_situ + factor * (pressure - s.in_situ);

  result.rows.push_back(compare("σ_r at r = " + format_fixed(probe->radius, 3) + " m", "MPa", -probe->rr / 1e6,
                                s.radial_stress(probe->radius, pressure) / 1e6, kSphericalCavityTolerance));
  result.rows.push_back(compare("σ_θ at r = " + format_fixed(probe->radius, 3) + " m", "MPa", -probe->tt / 1e6,
                                s.hoop_stress(probe->radius, pressure) / 1e6, kSphericalCavityTolerance));
  result.rows.push_back(compare("u_r at r = a", "mm", mean_radial_displacement(solver, "inner", true) * 1e3,
                                s.radial_displacement(s.radius, pressure) * 1e3, kSphericalCavityTolerance));
  result.rows.push_back(compare("first-yield cavity pressure p_y", "MPa", computed_yield / 1e6, s.first_yield_pressure() / 1e6, kSphericalCavityTolerance));
  // The load stays below first yield, so no tetrahedron may have yielded (a
  // load path with an inertial overshoot would show up here): a count,
  // compared absolutely (scale 1), so that any yielded tetrahedron fails the row.
  double yielded = 0.0;
  for (Index t = 0; t < solver.tetrahedra().size(); ++t)
    if (solver.tetrahedron_state(t)[constitutive::MohrCoulombModel::kPlasticShearStrain] > 0.0 ||
        solver.tetrahedron_state(t)[constitutive::MohrCoulombModel::kPlasticTensileStrain] > 0.0)
      yielded += 1.0;
  result.rows.push_back(compare("tetrahedra yielded at 0.9 of the way to p_y", "-", yielded, 0.0, kSphericalCavityTolerance, 1.0));
  result.mesh = lattice_text("sphere octant b = 5a, 3 patches", nr, n, n, mesh.zone_count());
  result.zones = mesh.zone_count();
  result.zone_size = s.radius * (spec.grading_ratio - 1.0);
  result.seconds = clock.seconds();
  return result;
}

}  // namespace dfc::fdm::verification
