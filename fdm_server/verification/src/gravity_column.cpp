// Gravity column: roller sides, fixed base, run to equilibrium with local
// damping from a stress-free start. Compared at zone centroids, where lumped
// gravity and constant zone stress make the discrete solution exact (§2(c)),
// so what remains is the convergence error.
#include "dfc/fdm/verification/gravity_column.hpp"

#include <cmath>
#include <memory>

#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/fdm/verification/fixtures.hpp"

namespace dfc::fdm::verification {

double GravityColumnData::constrained_modulus() const {
  return young_modulus * (1.0 - poisson_ratio) / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
}

double GravityColumnData::top_settlement() const { return density * gravity * height * height / (2.0 * constrained_modulus()); }

ProblemResult run_gravity_column(int level) {
  const Stopwatch clock;
  const GravityColumnData d;
  const Index zones = 11 * (Index(1) << level) - 1;
  SolverSettings settings = static_settings();
  settings.gravity = Vec3(0.0, 0.0, -d.gravity);
  Solver solver(make_box({Vec3::Zero(), Vec3(1.0, 1.0, d.height), {1, 1, zones}}),
                Material{d.density, std::make_unique<constitutive::ElasticModel>(constitutive::ElasticModel::from_young_poisson(d.young_modulus, d.poisson_ratio))},
                settings);
  for (const char* side : {"xmin", "xmax", "ymin", "ymax"}) solver.apply_boundary_condition({side, BoundaryKind::roller});
  solver.apply_boundary_condition({"zmin", BoundaryKind::fixed});

  ProblemResult result;
  result.steps = equilibrate(solver, "gravity column");
  const Index mid = zones / 2;
  const double depth = d.height - solver.mesh().zone_centroid(mid).z();
  const Stress s = solver.zone_stress(mid);
  double settlement = 0.0;
  const auto top = solver.mesh().face_group_gridpoints("zmax");
  for (const Index gp : top) settlement -= solver.displacements()[gp].z() / double(top.size());

  result.rows.push_back(compare("σv at mid-depth (d = " + format_fixed(depth, 2) + " m)", "kPa", -s.zz / 1e3,
                                d.vertical_stress(depth) / 1e3, kGravityColumnTolerance));
  result.rows.push_back(compare("σh at mid-depth", "kPa", -0.5 * (s.xx + s.yy) / 1e3, d.k0() * d.vertical_stress(depth) / 1e3, kGravityColumnTolerance));
  result.rows.push_back(compare("settlement of the top", "mm", settlement * 1e3, d.top_settlement() * 1e3, kGravityColumnTolerance));
  result.mesh = lattice_text("box", 1, 1, zones, solver.mesh().zone_count());
  result.zones = solver.mesh().zone_count();
  result.zone_size = d.height / double(zones);
  result.seconds = clock.seconds();
  return result;
}

}  // namespace dfc::fdm::verification
