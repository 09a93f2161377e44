#include "dfc/fdm/verification/fixtures.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "dfc/common/errors.hpp"
#include "dfc/fdm/boundary_conditions.hpp"
#include "dfc/fdm/equilibrium.hpp"
#include "dfc/fdm/hex_overlays.hpp"

namespace dfc::fdm::verification {

SolverSettings static_settings() {
  SolverSettings settings;
  settings.local_damping = 0.8;
  settings.mass_scaling = true;
  settings.threads = 1;
  return settings;
}

int equilibrate(Solver& solver, std::string_view problem, double target_ratio) {
  EquilibriumSettings settings;
  settings.target_ratio = target_ratio;
  const int steps = step_to_equilibrium(solver, settings);
  if (steps < 0)
    throw SolverError(std::string(problem) + ": no equilibrium (unbalanced-force ratio " + std::to_string(solver.unbalanced_force_ratio()) +
                      " after " + std::to_string(settings.max_steps) + " steps)");
  return steps;
}

void ramp_external_forces(Solver& solver, std::span<const Vec3> from, std::span<const Vec3> to, int steps) {
  for (int step = 1; step <= steps; ++step) {
    const double f = double(step) / double(steps);
    for (std::size_t gp = 0; gp < from.size(); ++gp) solver.set_external_force(gp, (1.0 - f) * from[gp] + f * to[gp]);
    solver.step(1.0);
  }
}

int load_in_stages(Solver& solver, std::span<const Vec3> from, std::span<const Vec3> to, int stages, std::string_view problem,
                   double stage_ratio) {
  int steps = 0;
  for (int stage = 1; stage <= stages; ++stage) {
    const double f = double(stage) / double(stages);
    for (std::size_t gp = 0; gp < from.size(); ++gp) solver.set_external_force(gp, (1.0 - f) * from[gp] + f * to[gp]);
    steps += equilibrate(solver, problem, stage_ratio);
  }
  return steps;
}

std::vector<Vec3> pressure_forces(const Mesh& mesh, std::string_view group, double pressure) {
  std::vector<Vec3> forces(mesh.gridpoint_count(), Vec3::Zero());
  add_face_loads(mesh, BoundaryCondition{std::string(group), BoundaryKind::pressure, pressure, Vec3::Zero()}, forces);
  return forces;
}

std::vector<Vec3> stress_field_forces(const Mesh& mesh, std::string_view group, const std::function<Stress(const Vec3&)>& stress_at) {
  std::vector<Vec3> forces(mesh.gridpoint_count(), Vec3::Zero());
  for (const FaceQuad& face : mesh.face_group(group)) {
    const Vec3 force = stress_at(mesh.face_centroid(face)).apply(quad_area_vector(mesh, face));
    for (const Index gp : face) forces[gp] += force / 4.0;
  }
  return forces;
}

CylindricalStress cylindrical_components(const Stress& stress, const Vec3& x) {
  const Vec3 radial = Vec3(x.x(), x.y(), 0.0).normalized();
  const Vec3 hoop(-radial.y(), radial.x(), 0.0);
  return {stress.normal_component(radial), stress.normal_component(hoop), hoop.dot(stress.apply(radial))};
}

SphericalStress spherical_components(const Stress& stress, const Vec3& x) {
  const double rr = stress.normal_component(x.normalized());
  return {rr, 0.5 * (stress.trace() - rr)};
}

CylinderCavitySpec quarter_annulus_spec(const QuarterAnnulus& annulus) {
  CylinderCavitySpec spec;
  spec.inner_radius = annulus.inner_radius;
  spec.outer_radius = annulus.outer_radius;
  spec.zones_radial = annulus.zones_radial;
  spec.zones_around = annulus.zones_around;
  spec.zones_vertical = 1;
  spec.angle_deg = 90.0;
  spec.grading_ratio = std::pow(annulus.outer_radius / annulus.inner_radius, 1.0 / double(annulus.zones_radial));
  // One zone thick: the thickness is that of the innermost zones, where the
  // error is measured. The far zones are then flat slabs, harmless in plane
  // strain (no variation along z), so the aspect-ratio check is off.
  spec.height = annulus.inner_radius * (spec.grading_ratio - 1.0);
  spec.max_aspect_ratio = std::numeric_limits<double>::infinity();
  return spec;
}

Solver make_quarter_annulus(const QuarterAnnulus& annulus, Material material) {
  Solver solver(make_cylinder_cavity(quarter_annulus_spec(annulus)), std::move(material), static_settings());
  for (const char* group : {"bottom", "top", "theta_min", "theta_max"}) solver.apply_boundary_condition({group, BoundaryKind::roller});
  return solver;
}

std::vector<LayerStress> radial_layers(const Solver& solver, Index zones_radial, bool spherical) {
  std::vector<LayerStress> layers(zones_radial);
  std::vector<double> volume(zones_radial, 0.0);
  for (Index zone = 0; zone < solver.mesh().zone_count(); ++zone) {
    const Index i = zone % zones_radial;
    const Vec3 c = solver.mesh().zone_centroid(zone);
    const Stress s = solver.zone_stress(zone);
    double v = 0.0;
    for (Index t = zone * kTetrahedraPerZone; t < (zone + 1) * kTetrahedraPerZone; ++t) v += solver.tetrahedra()[t].volume;
    LayerStress& layer = layers[i];
    if (spherical) {
      const SphericalStress p = spherical_components(s, c);
      layer.radius += v * c.norm();
      layer.rr += v * p.rr;
      layer.tt += v * p.tt;
    } else {
      const CylindricalStress p = cylindrical_components(s, c);
      layer.radius += v * std::hypot(c.x(), c.y());
      layer.rr += v * p.rr;
      layer.tt += v * p.tt;
      layer.zz += v * s.zz;
    }
    volume[i] += v;
  }
  for (Index i = 0; i < zones_radial; ++i) {
    layers[i].radius /= volume[i];
    layers[i].rr /= volume[i];
    layers[i].tt /= volume[i];
    layers[i].zz /= volume[i];
  }
  return layers;
}

double mean_radial_displacement(const Solver& solver, std::string_view group, bool spherical) {
  const std::vector<Index> gridpoints = solver.mesh().face_group_gridpoints(group);
  double sum = 0.0;
  for (const Index gp : gridpoints) {
    const Vec3& x = solver.mesh().points[gp];
    const Vec3 radial = spherical ? x.normalized() : Vec3(x.x(), x.y(), 0.0).normalized();
    sum += solver.displacements()[gp].dot(radial);
  }
  return sum / double(gridpoints.size());
}

double extrapolate_linear(double x, double x1, double y1, double x2, double y2) { return y1 + (y2 - y1) * (x - x1) / (x2 - x1); }

double extrapolate_quadratic(double x, const std::array<double, 3>& xs, const std::array<double, 3>& ys) {
  double y = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    double basis = 1.0;
    for (std::size_t j = 0; j < 3; ++j)
      if (j != i) basis *= (x - xs[j]) / (xs[i] - xs[j]);
    y += basis * ys[i];
  }
  return y;
}

LineFit fit_line(std::span<const double> x, std::span<const double> y) {
  const double n = double(x.size());
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  return {(sy - slope * sx) / n, slope};
}

std::string format_fixed(double value, int decimals) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(decimals);
  out << value;
  return out.str();
}

std::string lattice_text(std::string_view kind, Index n1, Index n2, Index n3, std::size_t zones) {
  return std::string(kind) + " " + std::to_string(n1) + "×" + std::to_string(n2) + "×" + std::to_string(n3) + " (" +
         std::to_string(zones) + " zones)";
}

}  // namespace dfc::fdm::verification
