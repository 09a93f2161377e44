// Wave in a bar: box of 1×1×n cubic zones along z with roller sides (1-D
// strain), a velocity step on zmin and a fixed far end. The stress history of
// the zone at the station gives the plateau (the mean between the front's
// passage and the return of the reflection, which averages the Gibbs
// oscillations behind the front) and the arrival time, taken as the centroid
// of the stress rise, t_a = ∫ t dσ / σ_p = T − (1/σ_p) ∫₀ᵀ σ dt. The explicit
// scheme disperses the front into an Airy-like ramp whose width grows as
// (x Δz²)^{1/3}; its centroid travels at the long-wave speed C_p, whereas a
// half-amplitude crossing lags by a fraction of that width.
#include "dfc/fdm/verification/wave_bar.hpp"

#include <cmath>
#include <memory>
#include <vector>

#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/fdm/mesh_generators.hpp"
#include "dfc/fdm/verification/fixtures.hpp"

namespace dfc::fdm::verification {

double WaveBarData::p_wave_speed() const {
  const double constrained = young_modulus * (1.0 - poisson_ratio) / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  return std::sqrt(constrained / density);
}

ProblemResult run_wave_bar(int level) {
  const Stopwatch clock;
  const WaveBarData d;
  const Index n = 50 * (Index(1) << level);
  const double dz = d.length / double(n);
  SolverSettings settings = static_settings();
  settings.local_damping = 0.0;  // §2(e): no local damping, real masses
  settings.mass_scaling = false;
  Solver solver(make_box({Vec3::Zero(), Vec3(dz, dz, d.length), {1, 1, n}}),
                Material{d.density, std::make_unique<constitutive::ElasticModel>(constitutive::ElasticModel::from_young_poisson(d.young_modulus, d.poisson_ratio))},
                settings);
  for (const char* side : {"xmin", "xmax", "ymin", "ymax"}) solver.apply_boundary_condition({side, BoundaryKind::roller});
  solver.apply_boundary_condition({"zmax", BoundaryKind::fixed});
  for (const Index gp : solver.mesh().face_group_gridpoints("zmin")) solver.prescribe_velocity(gp, Vec3(0.0, 0.0, d.velocity));

  const Index station_zone = Index(d.station / dz);  // centroid at (k + ½) dz, the zone containing the station
  const double station = (double(station_zone) + 0.5) * dz;
  Index station_gp = 0;  // a gridpoint at the station's height (zone bottom)
  for (Index gp = 0; gp < solver.mesh().gridpoint_count(); ++gp)
    if (std::abs(solver.mesh().points[gp].z() - double(station_zone) * dz) < 1e-9 * d.length) station_gp = gp;

  const double c = d.p_wave_speed();
  const double dt = solver.critical_timestep();
  const double window_start = (station + 2.0) / c;             // 2 m behind the front
  const double window_end = (2.0 * d.length - station - 1.0) / c;  // 1 m before the reflection
  std::vector<double> time, stress;
  double plateau = 0.0, velocity = 0.0;
  int samples = 0;
  for (double t = dt; t <= window_end; t += dt) {
    solver.step(dt);
    time.push_back(t);
    stress.push_back(-solver.zone_stress(station_zone).zz);  // compressive
    if (t >= window_start) {
      plateau += stress.back();
      velocity += solver.velocities()[station_gp].z();
      ++samples;
    }
  }
  plateau /= samples;
  velocity /= samples;
  double integral = 0.0;  // ∫₀ᵀ σ dt, trapezoidal, σ(0) = 0
  for (std::size_t i = 0; i < stress.size(); ++i) integral += 0.5 * (stress[i] + (i > 0 ? stress[i - 1] : 0.0)) * dt;
  const double arrival = time.back() - integral / plateau;

  ProblemResult result;
  result.steps = int(time.size());
  result.rows.push_back(compare("arrival time at x = " + format_fixed(station, 2) + " m", "ms", arrival * 1e3, station / c * 1e3, kWaveBarTolerance));
  result.rows.push_back(compare("stress behind the front", "kPa", plateau / 1e3, d.stress_jump() / 1e3, kWaveBarTolerance));
  result.rows.push_back(compare("particle velocity behind the front", "mm/s", velocity * 1e3, d.velocity * 1e3, kWaveBarTolerance));
  result.mesh = lattice_text("bar", 1, 1, n, solver.mesh().zone_count());
  result.zones = solver.mesh().zone_count();
  result.zone_size = dz;
  result.seconds = clock.seconds();
  return result;
}

}  // namespace dfc::fdm::verification
