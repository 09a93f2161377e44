// Lamé cylinder on a plane-strain quarter annulus: pressure on the cavity
// wall, free outer wall. Stresses are ring averages of the zone stresses
// compared with the closed form at the ring's mean centroid radius.
#include "dfc/fdm/verification/lame_cylinder.hpp"

#include <algorithm>
#include <cmath>
#include <vector>
#include <memory>

#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/fdm/verification/fixtures.hpp"

namespace dfc::fdm::verification {

double LameSolution::a_coefficient() const {
  const double a2 = inner_radius * inner_radius;
  const double b2 = outer_radius * outer_radius;
  if (outer_wall_held) return -inner_pressure / (1.0 + (1.0 - 2.0 * poisson_ratio) * b2 / a2);
  return (inner_pressure * a2 - outer_pressure * b2) / (b2 - a2);
}

double LameSolution::b_coefficient() const {
  const double a2 = inner_radius * inner_radius;
  const double b2 = outer_radius * outer_radius;
  if (outer_wall_held) return -(1.0 - 2.0 * poisson_ratio) * a_coefficient() * b2;
  return (inner_pressure - outer_pressure) * a2 * b2 / (b2 - a2);
}

double LameSolution::radial_stress(double r) const { return a_coefficient() - b_coefficient() / (r * r); }
double LameSolution::hoop_stress(double r) const { return a_coefficient() + b_coefficient() / (r * r); }

double LameSolution::radial_displacement(double r) const {
  const double shear = young_modulus / (2.0 * (1.0 + poisson_ratio));
  return r / (2.0 * shear) * ((1.0 - 2.0 * poisson_ratio) * a_coefficient() + b_coefficient() / (r * r));
}

ProblemResult run_lame_cylinder(int level) {
  const Stopwatch clock;
  const LameSolution exact;
  const Index n = 8 * (Index(1) << level);
  const QuarterAnnulus annulus{exact.inner_radius, exact.outer_radius, n, n};
  Solver solver = make_quarter_annulus(
      annulus, Material{2000.0, std::make_unique<constitutive::ElasticModel>(constitutive::ElasticModel::from_young_poisson(exact.young_modulus, exact.poisson_ratio))});
  solver.apply_boundary_condition({"inner", BoundaryKind::pressure, exact.inner_pressure});

  ProblemResult result;
  result.steps = equilibrate(solver, "Lamé cylinder");
  const std::vector<LayerStress> rings = radial_layers(solver, n, false);
  const LayerStress& inner = rings.front();
  // The ring whose centroid is nearest the mid-wall radius.
  const double mid = 0.5 * (exact.inner_radius + exact.outer_radius);
  const LayerStress& middle = *std::min_element(rings.begin(), rings.end(), [&](const LayerStress& x, const LayerStress& y) {
    return std::abs(x.radius - mid) < std::abs(y.radius - mid);
  });

  result.rows.push_back(compare("σ_θ, innermost ring (r = " + format_fixed(inner.radius, 3) + " m)", "MPa", inner.tt / 1e6,
                                exact.hoop_stress(inner.radius) / 1e6, kLameTolerance));
  result.rows.push_back(compare("σ_r, mid-wall ring (r = " + format_fixed(middle.radius, 3) + " m)", "MPa", middle.rr / 1e6,
                                exact.radial_stress(middle.radius) / 1e6, kLameTolerance));
  result.rows.push_back(compare("σ_θ, mid-wall ring (r = " + format_fixed(middle.radius, 3) + " m)", "MPa", middle.tt / 1e6,
                                exact.hoop_stress(middle.radius) / 1e6, kLameTolerance));
  result.rows.push_back(compare("u_r at r = a", "mm", mean_radial_displacement(solver, "inner") * 1e3,
                                exact.radial_displacement(exact.inner_radius) * 1e3, kLameTolerance));
  result.rows.push_back(compare("u_r at r = b", "mm", mean_radial_displacement(solver, "outer") * 1e3,
                                exact.radial_displacement(exact.outer_radius) * 1e3, kLameTolerance));
  result.mesh = lattice_text("quarter annulus b = 3a,", n, n, 1, solver.mesh().zone_count());
  result.zones = solver.mesh().zone_count();
  result.zone_size = exact.inner_radius * (quarter_annulus_spec(annulus).grading_ratio - 1.0);
  result.seconds = clock.seconds();
  return result;
}

}  // namespace dfc::fdm::verification
