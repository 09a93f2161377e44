// Kirsch hole on a plane-strain quarter annulus (symmetry planes x = 0, y = 0):
// p1 acts along y, p2 along x, so θ (from p1) = atan2(x, y). The in-situ stress
// is the initial stress, the cavity wall is free, and the outer boundary
// carries the closed-form traction σ·n: the finite annulus then has the
// infinite medium's solution, and the displacement is the one caused by the
// excavation, as in the closed form.
#include "dfc/fdm/verification/kirsch_hole.hpp"

#include <cmath>
#include <memory>
#include <numbers>

#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/fdm/verification/fixtures.hpp"

namespace dfc::fdm::verification {

namespace {


double angle_from_p1(const Vec3& x) { return std::atan2(x.x(), x.y()); }

// The closed-form stress tensor (tension positive, Cartesian) at x: the polar
// components in the frame e_r = (sinθ, cosθ), e_θ = (cosθ, −sinθ) of θ from y.
Stress cartesian_stress(const KirschSolution& k, const Vec3& x) {
  const double r = std::hypot(x.x(), x.y());
  const double theta = angle_from_p1(x);
  const Eigen::Vector2d er(std::sin(theta), std::cos(theta));
  const Eigen::Vector2d et(std::cos(theta), -std::sin(theta));
  const Eigen::Matrix2d polar = -(k.radial_stress(r, theta) * er * er.transpose() + k.hoop_stress(r, theta) * et * et.transpose() +
                                  k.shear_stress(r, theta) * (er * et.transpose() + et * er.transpose()));
  return Stress{polar(0, 0), polar(1, 1), 0.0, polar(0, 1), 0.0, 0.0};
}

// Hoop stress (compression positive) of the zone at (ring, column) and its centroid.
struct ZoneHoop {
  double r = 0.0, theta = 0.0, hoop = 0.0;
};
ZoneHoop zone_hoop(const Solver& solver, Index ring, Index column, Index zones_radial) {
  const Index zone = ring + zones_radial * column;
  const Vec3 c = solver.mesh().zone_centroid(zone);
  return {std::hypot(c.x(), c.y()), angle_from_p1(c), -cylindrical_components(solver.zone_stress(zone), c).tt};
}

}  // namespace

double KirschSolution::poisson_ratio() const { return (3.0 * bulk_modulus - 2.0 * shear_modulus) / (2.0 * (3.0 * bulk_modulus + shear_modulus)); }

double KirschSolution::radial_stress(double r, double theta) const {
  const double q = radius * radius / (r * r);
  return 0.5 * (p1 + p2) * (1.0 - q) + 0.5 * (p1 - p2) * (1.0 - 4.0 * q + 3.0 * q * q) * std::cos(2.0 * theta);
}

double KirschSolution::hoop_stress(double r, double theta) const {
  const double q = radius * radius / (r * r);
  return 0.5 * (p1 + p2) * (1.0 + q) - 0.5 * (p1 - p2) * (1.0 + 3.0 * q * q) * std::cos(2.0 * theta);
}

double KirschSolution::shear_stress(double r, double theta) const {
  const double q = radius * radius / (r * r);
  return -0.5 * (p1 - p2) * (1.0 + 2.0 * q - 3.0 * q * q) * std::sin(2.0 * theta);
}

double KirschSolution::radial_displacement_towards_hole(double r, double theta) const {
  const double g4 = 4.0 * shear_modulus;
  const double q = radius * radius / r;
  return (p1 + p2) / g4 * q + (p1 - p2) / g4 * q * (4.0 * (1.0 - poisson_ratio()) - radius * radius / (r * r)) * std::cos(2.0 * theta);
}

ProblemResult run_kirsch_hole(int level) {
  const Stopwatch clock;
  const KirschSolution k;
  const Index n = 12 * (Index(1) << level);
  const QuarterAnnulus annulus{k.radius, 6.0 * k.radius, n, n};
  Solver solver = make_quarter_annulus(annulus, Material{2600.0, std::make_unique<constitutive::ElasticModel>(constitutive::ElasticModuli{k.bulk_modulus, k.shear_modulus})});
  solver.set_initial_stress([&](const Vec3&) { return Stress{-k.p2, -k.p1, -k.poisson_ratio() * (k.p1 + k.p2), 0.0, 0.0, 0.0}; });
  const std::vector<Vec3> outer = stress_field_forces(solver.mesh(), "outer", [&](const Vec3& x) { return cartesian_stress(k, x); });
  for (std::size_t gp = 0; gp < outer.size(); ++gp) solver.set_external_force(gp, outer[gp]);

  ProblemResult result;
  result.steps = equilibrate(solver, "Kirsch hole");

  // Wall hoop stress: the two innermost zones of the column next to each
  // symmetry plane, extrapolated linearly in r to r = a. Column 0 is next to
  // the x axis (θ ≈ 90° from p1), column n−1 next to the y axis (θ ≈ 0°).
  for (const Index column : {Index(0), n - 1}) {
    const ZoneHoop z1 = zone_hoop(solver, 0, column, n);
    const ZoneHoop z2 = zone_hoop(solver, 1, column, n);
    const ZoneHoop z3 = zone_hoop(solver, 2, column, n);
    const double wall = extrapolate_quadratic(k.radius, {z1.r, z2.r, z3.r}, {z1.hoop, z2.hoop, z3.hoop});
    const double theta = z1.theta;
    result.rows.push_back(compare("σ_θ at the wall, θ = " + format_fixed(theta * 180.0 / std::numbers::pi, 1) + "°", "MPa", wall / 1e6,
                                  k.hoop_stress(k.radius, theta) / 1e6, kKirschTolerance));
  }
  // Decay with r along the column next to the x axis, where σ_θ is largest.
  for (const double target : {2.0, 4.0}) {
    Index best = 0;
    for (Index i = 0; i < n; ++i)
      if (std::abs(zone_hoop(solver, i, 0, n).r - target * k.radius) < std::abs(zone_hoop(solver, best, 0, n).r - target * k.radius)) best = i;
    const ZoneHoop z = zone_hoop(solver, best, 0, n);
    result.rows.push_back(compare("σ_θ at r = " + format_fixed(z.r / k.radius, 2) + "a, θ = " + format_fixed(z.theta * 180.0 / std::numbers::pi, 1) + "°",
                                  "MPa", z.hoop / 1e6, k.hoop_stress(z.r, z.theta) / 1e6, kKirschTolerance));
  }
  // Wall convergence at the top of the hole (gridpoint on the y axis, θ = 0).
  for (const Index gp : solver.mesh().face_group_gridpoints("inner")) {
    const Vec3& x = solver.mesh().points[gp];
    if (x.x() != 0.0 || x.z() != 0.0) continue;
    const double towards = -solver.displacements()[gp].dot(x.normalized());
    result.rows.push_back(compare("u_r towards the hole at r = a, θ = 0°", "mm", towards * 1e3,
                                  k.radial_displacement_towards_hole(k.radius, 0.0) * 1e3, kKirschTolerance));
  }
  result.mesh = lattice_text("quarter annulus b = 6a,", n, n, 1, solver.mesh().zone_count());
  result.zones = solver.mesh().zone_count();
  result.zone_size = k.radius * (quarter_annulus_spec(annulus).grading_ratio - 1.0);
  result.seconds = clock.seconds();
  return result;
}

}  // namespace dfc::fdm::verification
