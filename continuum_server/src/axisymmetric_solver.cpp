#include "dfc/continuum/axisymmetric_solver.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "dfc/continuum/darcy_flow.hpp"
#include "dfc/continuum/local_damping.hpp"
#include "dfc/continuum/nodal_average.hpp"

namespace dfc::continuum {

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
  pore_pressures_.assign(nodes, 0.0);
  pore_pressure_prescribed_.assign(nodes, false);
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

void AxisymmetricSolver::prescribe_pore_pressure(std::span<const Index> nodes, double pressure) {
  assert(settings_.pore_water.enabled && "pore pressures need SolverSettings::pore_water.enabled");
  for (const Index n : nodes) {
    pore_pressure_prescribed_[n] = true;
    pore_pressures_[n] = pressure;
  }
}

void AxisymmetricSolver::apply_pressure(const std::string& edge_group, double pressure) {
  (void)mesh_.edge_group(edge_group);  // asserts that it exists
  pressures_.emplace_back(edge_group, pressure);
}

void AxisymmetricSolver::step() {
  move_and_update_stresses();
  if (pile_) pile_->move();
  compute_forces_and_masses();
  update_velocities();
  ++steps_;
}

double AxisymmetricSolver::undrained_bulk_modulus() const {
  const double bulk = model_->stiffest_moduli().bulk;
  if (!settings_.pore_water.enabled) return bulk;
  const double alpha = settings_.pore_water.biot_coefficient;
  // Undrained, the water adds α² M_w to the skeleton's bulk modulus (Biot
  // 1941, doi:10.1063/1.1712886; Skempton 1954): it sizes the masses.
  return bulk + alpha * alpha * settings_.pore_water.biot_modulus();
}

std::vector<double> AxisymmetricSolver::volumetric_field(std::span<const double> volumes, std::span<const double> values) {
  const Index nodes = mesh_.nodes.size();
  switch (settings_.volumetric_strain) {
    case VolumetricStrain::element:
      break;
    case VolumetricStrain::nodal_average:
      return nodal_average(mesh_.triangles, nodes, volumes, values);
    case VolumetricStrain::pressure_projection: {
      // Dohrmann & Bochev (2004): weight τ = K/G of the projection term for
      // the skeleton (the pore water has its own, water_operator()).
      const constitutive::ElasticModuli moduli = model_->stiffest_moduli();
      const double weight = settings_.pressure_stabilisation * moduli.bulk / moduli.shear;
      return triangle_means(mesh_.triangles, projection_.nodal_solution(mesh_.triangles, nodes, volumes, weight, values));
    }
  }
  return {values.begin(), values.end()};
}

ProjectionOperator AxisymmetricSolver::water_operator() const {
  // Dohrmann & Bochev's (2004) projection for the water's pressure: the
  // undrained constraint is the water's, its "bulk modulus" α² M_w, so the
  // skeleton's (M + (α² M_w/G) S) e = B Δε_v with e = −Δp_w/(α M_w) reads
  // (M/M_w + (α²/G) S) Δp_w = −α B Δε_v: storage c = 1/M_w, weight τ_w = α²/G.
  const double alpha = settings_.pore_water.biot_coefficient;
  return {1.0 / settings_.pore_water.biot_modulus(),
          settings_.pressure_stabilisation * alpha * alpha / model_->stiffest_moduli().shear};
}

Stress AxisymmetricSolver::total_stress(Index triangle) const {
  const Triangle& tri = mesh_.triangles[triangle];
  const double mean_pore_pressure = (pore_pressures_[tri[0]] + pore_pressures_[tri[1]] + pore_pressures_[tri[2]]) / 3.0;
  // σ = σ′ − α p_w I (tension positive, p_w compression positive; Biot 1941).
  return stresses_[triangle] - SymTensor::isotropic(settings_.pore_water.biot_coefficient * mean_pore_pressure);
}

void AxisymmetricSolver::advance_flow() {
  flow_substeps_ = 0;
  const PoreWaterSettings& water = settings_.pore_water;
  if (!water.enabled || water.time_per_step <= 0.0) return;
  const Index nodes = mesh_.nodes.size();
  // Lumped storage C_i = (Σ_e V_e/3)/M_w, m³/Pa.
  std::vector<double> storage(nodes, 0.0);
  for (const Triangle& tri : mesh_.triangles) {
    const double volume = triangle_geometry(gather(mesh_.nodes, tri)).volume();
    for (const Index n : tri) storage[n] += volume / 3.0 / water.biot_modulus();
  }
  std::vector<bool> free_nodes(nodes);
  for (Index n = 0; n < nodes; ++n) free_nodes[n] = !pore_pressure_prescribed_[n];
  // The water alone (the skeleton held during the substeps): Δt ≤ 2 C/Σ|H|,
  // h²/(2 k M_w/γ_w) in 1-D. 0.9: the Gershgorin bound is attained in 1-D,
  // where at the bound itself the shortest mode would not decay.
  const double stable = 0.9 * stable_flow_step(storage, darcy_row_sums(mesh_.nodes, mesh_.triangles, water.mobility()), free_nodes);
  const double substeps = std::ceil(water.time_per_step / stable);
  if (substeps > water.max_flow_substeps) {
    std::ostringstream message;
    message << "continuum pore water: the flow needs " << substeps << " substeps per step (stable flow step " << stable
            << " s for time_per_step " << water.time_per_step << " s; the bound is h^2/(2 k M_w/gamma_w) with M_w = K_f/n = "
            << water.biot_modulus() << " Pa); lower PoreWaterSettings::time_per_step or raise max_flow_substeps ("
            << water.max_flow_substeps << "), or soften fluid_bulk_modulus where the problem allows";
    throw std::runtime_error(message.str());
  }
  flow_substeps_ = static_cast<int>(substeps);
  const double dt = water.time_per_step / substeps;
  const bool stabilised = settings_.volumetric_strain == VolumetricStrain::pressure_projection;
  std::vector<double> volumes;
  if (stabilised)
    for (const Triangle& tri : mesh_.triangles) volumes.push_back(triangle_geometry(gather(mesh_.nodes, tri)).volume());
  for (int s = 0; s < flow_substeps_; ++s) {
    std::vector<double> outflow = darcy_outflow(mesh_.nodes, mesh_.triangles, water.mobility(), pore_pressures_);
    if (stabilised) {
      // (C + τ_w S) Δp = −Δt H p: the stabilisation acts on the whole pore
      // pressure change, as in the stabilised mass balance of White & Borja
      // (2008, doi:10.1016/j.cma.2008.05.015); C + τ_w S ≥ C, so the lumped bound above stays stable.
      for (double& q : outflow) q *= -dt;
      const std::vector<double> change = water_projection_.solve(mesh_.triangles, volumes, water_operator(), pore_pressure_prescribed_, outflow);
      for (Index n = 0; n < nodes; ++n) pore_pressures_[n] += change[n];
    } else {
      for (Index n = 0; n < nodes; ++n)
        if (free_nodes[n]) pore_pressures_[n] -= dt * outflow[n] / storage[n];
    }
  }
  flow_time_ += water.time_per_step;
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
  // Volumetric part from the nodal field (docs/continuum_pile.md §3), deviatoric part kept.
  const std::vector<double> treated = volumetric_field(volumes, volumetric);
  for (Index t = 0; t < triangles; ++t) strain_increments[t] += SymTensor::isotropic((treated[t] - volumetric[t]) / 3.0);
  if (settings_.pore_water.enabled) {
    // The volume change's part of the fluid balance (Biot 1941), C Δp_w = −α B Δε_v:
    // with the projection, C + τ_w S in place of C (water_operator()).
    const double alpha = settings_.pore_water.biot_coefficient;
    if (settings_.volumetric_strain == VolumetricStrain::pressure_projection) {
      std::vector<double> rhs(mesh_.nodes.size(), 0.0);
      for (Index t = 0; t < triangles; ++t)
        for (const Index n : mesh_.triangles[t]) rhs[n] -= alpha * volumes[t] * volumetric[t] / 3.0;
      const std::vector<double> change = water_projection_.solve(mesh_.triangles, volumes, water_operator(), pore_pressure_prescribed_, rhs);
      for (Index n = 0; n < mesh_.nodes.size(); ++n) pore_pressures_[n] += change[n];
    } else {
      // Lumped: Δp_w = −α M_w Δε̄_v(n), the nodal mean strain.
      const std::vector<double> nodal = nodal_means(mesh_.triangles, mesh_.nodes.size(), volumes, volumetric);
      for (Index n = 0; n < mesh_.nodes.size(); ++n)
        if (!pore_pressure_prescribed_[n]) pore_pressures_[n] -= alpha * settings_.pore_water.biot_modulus() * nodal[n];
    }
  }

  for (Index n = 0; n < mesh_.nodes.size(); ++n) mesh_.nodes[n] += velocities_[n];

  const std::size_t state_size = model_->state_size();
  const double bulk = model_->stiffest_moduli().bulk;
  std::vector<double> plastic_mean_change(triangles);
  for (Index t = 0; t < triangles; ++t) {
    Stress& stress = stresses_[t];
    rotate_by_jaumann(stress, spin_increments[t]);
    const double mean_before = stress.trace() / 3.0;
    const Stress before = stress;
    model_->update(constitutive::StrainIncrement{strain_increments[t]}, stress,
                   std::span(model_state_).subspan(t * state_size, state_size));
    if (!std::isfinite(stress.trace())) throw_failed_update(t, before, strain_increments[t]);
    plastic_mean_change[t] = stress.trace() / 3.0 - mean_before - bulk * strain_increments[t].trace();
  }
  // Models with plastic volume change: the plastic part of the mean-stress
  // change is averaged the same way (the elastic part already is, through the
  // strain), the counterpart of fdm_models.md §2 choice 9. Averaging the whole
  // change would smooth the elastic part twice.
  if (model_->needs_mean_stress_averaging() && settings_.volumetric_strain != VolumetricStrain::element) {
    const std::vector<double> smoothed = volumetric_field(volumes, plastic_mean_change);
    // The smoothing can move a state off a yield surface that has shrunk to
    // nearly a point (a fully destructured Cam clay): a zero-strain update
    // returns it; where that fails the unsmoothed state is kept.
    for (Index t = 0; t < triangles; ++t) (void)admit_stress(t, stresses_[t] + SymTensor::isotropic(smoothed[t] - plastic_mean_change[t]));
  }
  advance_flow();
}

bool AxisymmetricSolver::admit_stress(Index triangle, Stress stress) {
  const std::size_t state_size = model_->state_size();
  const auto first = model_state_.begin() + std::ptrdiff_t(triangle * state_size);
  std::vector<double> state(first, first + std::ptrdiff_t(state_size));
  model_->update(constitutive::StrainIncrement{SymTensor{}}, stress, state);
  if (!std::isfinite(stress.trace())) return false;
  stresses_[triangle] = stress;
  std::copy(state.begin(), state.end(), first);
  return true;
}

void AxisymmetricSolver::throw_failed_update(Index triangle, const Stress& before, const SymTensor& strain_increment) const {
  const Triangle& tri = mesh_.triangles[triangle];
  const Point centroid = (mesh_.nodes[tri[0]] + mesh_.nodes[tri[1]] + mesh_.nodes[tri[2]]) / 3.0;
  std::ostringstream message;
  message << "continuum: the constitutive update of triangle " << triangle << " at (r, z) = (" << centroid.x() << ", " << centroid.y()
          << ") m failed at step " << steps_ + 1 << " (stress before, Pa, rr θθ zz rz: " << before.xx << " " << before.yy << " "
          << before.zz << " " << before.zx << "; strain increment: " << strain_increment.xx << " " << strain_increment.yy << " "
          << strain_increment.zz << " " << strain_increment.zx << "; history:";
  const std::size_t state_size = model_->state_size();
  for (std::size_t s = 0; s < state_size; ++s) message << " " << model_state_[triangle * state_size + s];
  message << ")";
  throw std::runtime_error(message.str());
}

void AxisymmetricSolver::compute_forces_and_masses() {
  std::fill(internal_forces_.begin(), internal_forces_.end(), Point::Zero());
  std::fill(external_forces_.begin(), external_forces_.end(), Point::Zero());
  std::fill(masses_.begin(), masses_.end(), 0.0);
  const double shear = model_->stiffest_moduli().shear;
  const double bulk = undrained_bulk_modulus();
  for (Index t = 0; t < mesh_.triangles.size(); ++t) {
    const Triangle& tri = mesh_.triangles[t];
    const TriangleGeometry g = triangle_geometry(gather(mesh_.nodes, tri));
    const NodalVectors f = internal_forces(g, settings_.pore_water.enabled ? total_stress(t) : stresses_[t]);
    const std::array<double, 3> rows = stiffness_row_sums(g, bulk, shear);
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

void AxisymmetricSolver::apply_pile_contact() {
  const Index nodes = mesh_.nodes.size();
  pile_contacts_.assign(nodes, NodeContact{});
  for (Index n = 0; n < nodes; ++n) {
    ContactNodeState state{mesh_.nodes[n], velocities_[n], velocities_[n], external_forces_[n] - internal_forces_[n],
                           masses_[n],     settings_.damping, prescribed_[n]};
    for (Eigen::Index a = 0; a < 2; ++a)
      state.trial_velocity[a] = prescribed_[n][static_cast<std::size_t>(a)]
                                    ? prescribed_velocities_[n][a]
                                    : velocities_[n][a] + damped_velocity_change(state.force[a], velocities_[n][a], masses_[n],
                                                                                 settings_.damping);
    pile_contacts_[n] = pile_->contact(state);
    // The contact force is external: the update below then moves the node onto the face.
    external_forces_[n] += pile_contacts_[n].force;
  }
}

void AxisymmetricSolver::update_velocities() {
  if (pile_) apply_pile_contact();
  unbalanced_force_ratio_ = measure_unbalanced_force_ratio();
  for (Index n = 0; n < mesh_.nodes.size(); ++n) {
    for (Eigen::Index a = 0; a < 2; ++a) {
      if (prescribed_[n][static_cast<std::size_t>(a)]) {
        velocities_[n][a] = prescribed_velocities_[n][a];
        continue;
      }
      const double force = external_forces_[n][a] - internal_forces_[n][a];
      velocities_[n][a] += damped_velocity_change(force, velocities_[n][a], masses_[n], settings_.damping);
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

double AxisymmetricSolver::kinetic_energy() const {
  double sum = 0.0;
  for (Index n = 0; n < mesh_.nodes.size(); ++n) sum += 0.5 * masses_[n] * velocities_[n].squaredNorm();
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
