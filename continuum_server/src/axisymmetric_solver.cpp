#include "dfc/continuum/axisymmetric_solver.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

#include "dfc/continuum/nodal_average.hpp"

namespace dfc::continuum {

namespace {

double sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

}  // namespace

AxisymmetricSolver::AxisymmetricSolver(AxisymmetricMesh mesh, std::shared_ptr<const constitutive::ConstitutiveModel> model,
                                       const Stress& initial_stress, SolverSettings settings)
    : mesh_(std::move(mesh)), model_(std::move(model)), settings_(settings) {
  assert(model_);
  const Index nodes = mesh_.nodes.size();
  const Index triangles = mesh_.triangles.size();
  velocities_.assign(nodes, Point::Zero());
  internal_forces_.assign(nodes, Point::Zero());
  external_forces_.assign(nodes, Point::Zero());
  masses_.assign(nodes, 0.0);
  prescribed_.assign(nodes, {false, false});
  prescribed_velocities_.assign(nodes, Point::Zero());
  stresses_.assign(triangles, initial_stress);
  const std::size_t state_size = model_->state_size();
  model_state_.assign(triangles * state_size, 0.0);
  initial_areas_.reserve(triangles);
  for (Index t = 0; t < triangles; ++t) {
    model_->initialize_state(initial_stress, std::span(model_state_).subspan(t * state_size, state_size));
    const TriangleGeometry g = triangle_geometry(gather(mesh_.nodes, mesh_.triangles[t]));
    assert(g.area > 0.0 && "triangles must be counter-clockwise in (r, z)");
    initial_areas_.push_back(g.area);
    triangle_masses_.push_back(settings_.density * g.volume());
  }
}

void AxisymmetricSolver::prescribe_velocity(std::span<const Index> nodes, Axis axis, double velocity) {
  const auto a = static_cast<std::size_t>(axis);
  for (const Index n : nodes) {
    prescribed_[n][a] = true;
    prescribed_velocities_[n][static_cast<Eigen::Index>(a)] = velocity;
    velocities_[n][static_cast<Eigen::Index>(a)] = velocity;
  }
}

void AxisymmetricSolver::apply_pressure(const std::string& edge_group, double pressure) {
  (void)mesh_.edge_group(edge_group);  // asserts that it exists
  pressures_.emplace_back(edge_group, pressure);
}

void AxisymmetricSolver::step() {
  move_and_update_stresses();
  compute_forces_and_masses();
  update_velocities();
  ++steps_;
}

void AxisymmetricSolver::move_and_update_stresses() {
  const Index triangles = mesh_.triangles.size();
  // Strain and spin increments on the mid-step geometry x + ½vΔt: second-order
  // accurate in the step, and exactly the logarithmic strain increment of a
  // uniform stretch with fixed axes (docs/continuum_pile.md §2).
  std::vector<Point> midpoints(mesh_.nodes.size());
  for (Index n = 0; n < mesh_.nodes.size(); ++n) midpoints[n] = mesh_.nodes[n] + 0.5 * velocities_[n];
  std::vector<SymTensor> strain_increments(triangles);
  std::vector<double> spin_increments(triangles);
  std::vector<double> volumes(triangles);
  std::vector<double> volumetric(triangles);
  for (Index t = 0; t < triangles; ++t) {
    const Triangle& tri = mesh_.triangles[t];
    const TriangleGeometry g = triangle_geometry(gather(midpoints, tri));
    const VelocityGradient l = velocity_gradient(g, gather(velocities_, tri));
    strain_increments[t] = rate_of_deformation(l);
    spin_increments[t] = spin_rz(l);
    volumes[t] = g.volume();
    volumetric[t] = strain_increments[t].trace();
  }
  // Bonet & Burton (1998): volumetric part from the nodal averages, deviatoric part kept.
  if (settings_.average_volumetric_strain) {
    const std::vector<double> averaged = nodal_average(mesh_.triangles, mesh_.nodes.size(), volumes, volumetric);
    for (Index t = 0; t < triangles; ++t) strain_increments[t] += SymTensor::isotropic((averaged[t] - volumetric[t]) / 3.0);
  }

  for (Index n = 0; n < mesh_.nodes.size(); ++n) mesh_.nodes[n] += velocities_[n];

  const std::size_t state_size = model_->state_size();
  const double bulk = model_->stiffest_moduli().bulk;
  std::vector<double> plastic_mean_change(triangles);
  for (Index t = 0; t < triangles; ++t) {
    Stress& stress = stresses_[t];
    rotate_by_jaumann(stress, spin_increments[t]);
    const double mean_before = stress.trace() / 3.0;
    model_->update(constitutive::StrainIncrement{strain_increments[t]}, stress,
                   std::span(model_state_).subspan(t * state_size, state_size));
    plastic_mean_change[t] = stress.trace() / 3.0 - mean_before - bulk * strain_increments[t].trace();
  }
  // Models with plastic volume change: the plastic part of the mean-stress
  // change is averaged the same way (the elastic part already is, through the
  // strain), the counterpart of fdm_models.md §2 choice 9. Averaging the whole
  // change would smooth the elastic part twice.
  if (model_->needs_mean_stress_averaging()) {
    const std::vector<double> smoothed = nodal_average(mesh_.triangles, mesh_.nodes.size(), volumes, plastic_mean_change);
    for (Index t = 0; t < triangles; ++t) stresses_[t] += SymTensor::isotropic(smoothed[t] - plastic_mean_change[t]);
  }
}

void AxisymmetricSolver::compute_forces_and_masses() {
  std::fill(internal_forces_.begin(), internal_forces_.end(), Point::Zero());
  std::fill(external_forces_.begin(), external_forces_.end(), Point::Zero());
  std::fill(masses_.begin(), masses_.end(), 0.0);
  const constitutive::ElasticModuli moduli = model_->stiffest_moduli();
  for (Index t = 0; t < mesh_.triangles.size(); ++t) {
    const Triangle& tri = mesh_.triangles[t];
    const TriangleGeometry g = triangle_geometry(gather(mesh_.nodes, tri));
    const NodalVectors f = internal_forces(g, stresses_[t]);
    const std::array<double, 3> rows = stiffness_row_sums(g, moduli.bulk, moduli.shear);
    for (int i = 0; i < 3; ++i) {
      internal_forces_[tri[i]] += f[i];
      // Central differences are stable for Δt ≤ 2/ω_max and ω_max² ≤ max_i Σ_j|K_ij|/m_i
      // (Gershgorin), so m_i ≥ ¼ Σ_j|K_ij| makes Δt = 1 stable.
      masses_[tri[i]] += settings_.mass_safety * 0.25 * rows[i];
    }
  }
  for (const auto& [group, pressure] : pressures_) {
    for (const Edge& e : mesh_.edge_group(group)) {
      const Point& a = mesh_.nodes[e[0]];
      const Point& b = mesh_.nodes[e[1]];
      const Point tangent = b - a;
      const double length = tangent.norm();
      const Point outward(tangent.y() / length, -tangent.x() / length);  // body on the left
      // Consistent load of a uniform pressure on the cone swept by the edge:
      // node share 2π L (2 r_i + r_j)/6.
      const double factor = 2.0 * std::numbers::pi * length / 6.0;
      external_forces_[e[0]] -= pressure * factor * (2.0 * a.x() + b.x()) * outward;
      external_forces_[e[1]] -= pressure * factor * (2.0 * b.x() + a.x()) * outward;
    }
  }
}

void AxisymmetricSolver::update_velocities() {
  unbalanced_force_ratio_ = measure_unbalanced_force_ratio();
  for (Index n = 0; n < mesh_.nodes.size(); ++n) {
    for (Eigen::Index a = 0; a < 2; ++a) {
      if (prescribed_[n][static_cast<std::size_t>(a)]) {
        velocities_[n][a] = prescribed_velocities_[n][a];
        continue;
      }
      const double force = external_forces_[n][a] - internal_forces_[n][a];
      // Local damping (Cundall 1987): F − α|F| sgn(v), v of the previous half step.
      const double damped = force - settings_.damping * std::abs(force) * sign(velocities_[n][a]);
      velocities_[n][a] += damped / masses_[n];
    }
  }
}

double AxisymmetricSolver::measure_unbalanced_force_ratio() const {
  double unbalanced = 0.0;
  double applied = 0.0;
  for (Index n = 0; n < mesh_.nodes.size(); ++n) {
    for (Eigen::Index a = 0; a < 2; ++a) {
      if (prescribed_[n][static_cast<std::size_t>(a)]) continue;
      unbalanced += std::abs(external_forces_[n][a] - internal_forces_[n][a]);
      applied += std::abs(internal_forces_[n][a]) + std::abs(external_forces_[n][a]);
    }
  }
  return applied > 0.0 ? unbalanced / applied : 0.0;
}

Point AxisymmetricSolver::internal_force_sum(std::span<const Index> nodes) const {
  Point sum = Point::Zero();
  for (const Index n : nodes) sum += internal_forces_[n];
  return sum;
}

double AxisymmetricSolver::total_mass() const {
  double sum = 0.0;
  for (const double m : triangle_masses_) sum += m;
  return sum;
}

double AxisymmetricSolver::smallest_angle_deg() const {
  double smallest = 180.0;
  for (const Triangle& t : mesh_.triangles) smallest = std::min(smallest, continuum::smallest_angle_deg(gather(mesh_.nodes, t)));
  return smallest;
}

double AxisymmetricSolver::smallest_area_ratio() const {
  double smallest = std::numeric_limits<double>::infinity();
  for (Index t = 0; t < mesh_.triangles.size(); ++t)
    smallest = std::min(smallest, triangle_geometry(gather(mesh_.nodes, mesh_.triangles[t])).area / initial_areas_[t]);
  return smallest;
}

}  // namespace dfc::continuum
