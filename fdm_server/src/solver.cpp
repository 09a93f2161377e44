#include "dfc/fdm/solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "dfc/common/errors.hpp"
#include "dfc/common/work_progress.hpp"
#include "dfc/fdm/hex_overlays.hpp"
#include "dfc/fdm/masses.hpp"
#include "dfc/fdm/mixed_discretization.hpp"

namespace dfc::fdm {

namespace {

// Below this many zones or gridpoints a pass is a few microseconds and
// starting a parallel region costs more than it saves.
constexpr std::ptrdiff_t kMinParallelItems = 2048;

double sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

std::string format_seconds(double seconds) {
  std::ostringstream out;
  out.precision(6);
  out << seconds << " s";
  return out.str();
}

}  // namespace

Solver::Solver(Mesh mesh, Material material, SolverSettings settings)
    : mesh_(std::move(mesh)), material_(std::move(material)), settings_(settings) {
  if (material_.model == nullptr) throw UserError("the FDM solver needs a constitutive model");
  if (!(material_.density > 0.0)) throw UserError("the FDM material density must be > 0 kg/m3");
  if (!(settings_.local_damping >= 0.0 && settings_.local_damping < 1.0)) throw UserError("local damping must be in [0, 1)");
  check_mesh_quality(mesh_);

  const std::size_t n_gp = mesh_.gridpoint_count();
  tetrahedra_.reserve(mesh_.zone_count() * kTetrahedraPerZone);
  for (Index zone = 0; zone < mesh_.zone_count(); ++zone) {
    work_progress::advance_every(std::int64_t(zone), 4096);  // the set-up of a large grid, before any step
    const auto tets = zone_tetrahedra(mesh_, zone);
    tetrahedra_.insert(tetrahedra_.end(), tets.begin(), tets.end());
  }

  // Gridpoint → tetrahedron incidences (CSR), filled in ascending tetrahedron
  // order: the fixed summation order that makes the force gather deterministic.
  incidence_offsets_.assign(n_gp + 1, 0);
  for (const Tetrahedron& tet : tetrahedra_)
    for (const Index gp : tet.nodes) ++incidence_offsets_[gp + 1];
  for (std::size_t gp = 0; gp < n_gp; ++gp) incidence_offsets_[gp + 1] += incidence_offsets_[gp];
  incidence_.resize(incidence_offsets_.back());
  std::vector<std::size_t> fill(incidence_offsets_.begin(), incidence_offsets_.end() - 1);
  for (std::size_t t = 0; t < tetrahedra_.size(); ++t)
    for (std::size_t n = 0; n < 4; ++n) incidence_[fill[tetrahedra_[t].nodes[n]]++] = 4 * t + n;
  for (std::size_t gp = 0; gp < n_gp; ++gp)
    if (incidence_offsets_[gp] == incidence_offsets_[gp + 1])
      throw UserError("mesh gridpoint " + std::to_string(gp) + " belongs to no zone; remove unused gridpoints");

  const double p_wave = material_.model->stiffest_moduli().p_wave();
  real_mass_ = lumped_masses(n_gp, tetrahedra_, material_.density);
  mass_scaling_coefficient_ = mass_scaling_coefficients(n_gp, tetrahedra_, p_wave);
  critical_timestep_ = fdm::critical_timestep(tetrahedra_, p_wave, material_.density);
  extra_mass_.assign(n_gp, 0.0);

  velocity_.assign(n_gp, Vec3::Zero());
  displacement_.assign(n_gp, Vec3::Zero());
  body_force_.resize(n_gp);
  // §1.7: ρ g V/4 per tetrahedron node, ×½ per overlay = (lumped real mass) × g.
  for (std::size_t gp = 0; gp < n_gp; ++gp) body_force_[gp] = real_mass_[gp] * settings_.gravity;
  face_load_.assign(n_gp, Vec3::Zero());
  external_force_.assign(n_gp, Vec3::Zero());
  fixed_.assign(n_gp, {false, false, false});
  radial_roller_.assign(n_gp, Vec3::Zero());
  prescribed_.assign(n_gp, 0);
  prescribed_velocity_.assign(n_gp, Vec3::Zero());
  unbalanced_magnitude_.assign(n_gp, 0.0);
  reaction_.assign(n_gp, Vec3::Zero());
  applied_magnitude_.assign(n_gp, 0.0);

  stress_.assign(tetrahedra_.size(), Stress{});
  model_state_.assign(tetrahedra_.size() * material_.model->state_size(), 0.0);
  tet_force_.resize(tetrahedra_.size());
  set_initial_stress([](const Vec3&) { return Stress{}; });
}

void Solver::apply_boundary_condition(const BoundaryCondition& condition) {
  const std::vector<Index> gridpoints = mesh_.face_group_gridpoints(condition.group);
  switch (condition.kind) {
    case BoundaryKind::fixed:
      for (const Index gp : gridpoints) fixed_[gp] = {true, true, true};
      break;
    case BoundaryKind::roller: {
      const auto roller = classify_roller(mesh_, condition.group);
      if (!roller)
        throw UserError("a roller needs a planar face group normal to x, y or z, or a cylindrical group about the z axis; \"" +
                        condition.group + "\" is neither");
      for (const Index gp : gridpoints) {
        if (roller->type == RollerConstraint::Type::axis) {
          fixed_[gp][std::size_t(roller->axis)] = true;
        } else {
          const Vec3& x = mesh_.points[gp];
          radial_roller_[gp] = Vec3(x.x(), x.y(), 0.0).normalized();
        }
      }
      break;
    }
    case BoundaryKind::pressure:
    case BoundaryKind::traction:
      add_face_loads(mesh_, condition, face_load_);
      break;
  }
}

void Solver::set_initial_stress(const std::function<Stress(const Vec3& zone_centroid)>& stress_at) {
  const std::size_t state_size = material_.model->state_size();
  for (Index zone = 0; zone < mesh_.zone_count(); ++zone) {
    work_progress::advance_every(std::int64_t(zone), 4096);
    const Stress stress = stress_at(mesh_.zone_centroid(zone));
    for (Index t = zone * kTetrahedraPerZone; t < (zone + 1) * kTetrahedraPerZone; ++t) {
      stress_[t] = stress;
      material_.model->initialize_state(stress, constitutive::StateSpan(model_state_).subspan(t * state_size, state_size));
    }
  }
  for (Index t = 0; t < tetrahedra_.size(); ++t) compute_tetrahedron_forces(t);
}

void Solver::set_external_force(Index gp, const Vec3& force) { external_force_.at(gp) = force; }

void Solver::reset_kinematics() {
  std::fill(velocity_.begin(), velocity_.end(), Vec3::Zero());
  std::fill(displacement_.begin(), displacement_.end(), Vec3::Zero());
}

std::span<const double> Solver::tetrahedron_state(Index tet) const {
  const std::size_t state_size = material_.model->state_size();
  return std::span<const double>(model_state_).subspan(tet * state_size, state_size);
}

void Solver::set_extra_mass(Index gp, double mass) {
  extra_mass_.at(gp) = mass;
  inertial_mass_stale_ = true;
}

void Solver::prescribe_velocity(Index gp, const Vec3& velocity) {
  prescribed_.at(gp) = 1;
  prescribed_velocity_[gp] = velocity;
}

double Solver::inertial_mass(Index gp, double dt) const {
  // §1.10 static: m = c Δt² makes Δt stable; never lighter than the real mass,
  // so steps at or below the critical one keep the real dynamics.
  if (!settings_.mass_scaling) return real_mass_[gp];
  return std::max(real_mass_[gp], mass_scaling_coefficient_[gp] * dt * dt);
}

void Solver::update_inertial_masses(double dt) {
  if (!inertial_mass_stale_ && dt == inertial_mass_dt_) return;
  inertial_mass_.resize(real_mass_.size());
  for (std::size_t gp = 0; gp < real_mass_.size(); ++gp) inertial_mass_[gp] = inertial_mass(gp, dt) + extra_mass_[gp];
  inertial_mass_dt_ = dt;
  inertial_mass_stale_ = false;
}

Stress Solver::zone_stress(Index zone) const {
  Stress sum;
  double volume = 0.0;
  for (Index t = zone * kTetrahedraPerZone; t < (zone + 1) * kTetrahedraPerZone; ++t) {
    sum += stress_[t] * tetrahedra_[t].volume;
    volume += tetrahedra_[t].volume;
  }
  return sum * (1.0 / volume);
}

Vec3 Solver::gathered_tetrahedron_force(Index gp) const {
  Vec3 sum = Vec3::Zero();
  for (std::size_t k = incidence_offsets_[gp]; k < incidence_offsets_[gp + 1]; ++k) sum += tet_force_[incidence_[k] / 4][incidence_[k] % 4];
  return sum;
}

Vec3 Solver::force_exerted_on_gridpoint(Index gp) const { return gathered_tetrahedron_force(gp) + body_force_[gp] + face_load_[gp]; }

Solver::GridpointForces Solver::gridpoint_forces(Index gp) const {
  GridpointForces forces{Vec3::Zero(), 0.0};
  for (std::size_t k = incidence_offsets_[gp]; k < incidence_offsets_[gp + 1]; ++k) {
    const Vec3& f = tet_force_[incidence_[k] / 4][incidence_[k] % 4];
    forces.net += f;
    forces.magnitude += f.norm();
  }
  forces.net += body_force_[gp] + face_load_[gp] + external_force_[gp];
  forces.magnitude += body_force_[gp].norm() + face_load_[gp].norm() + external_force_[gp].norm();
  return forces;
}

Vec3 Solver::constrained(Index gp, Vec3 v) const {
  if (radial_roller_[gp].squaredNorm() > 0.0) v -= v.dot(radial_roller_[gp]) * radial_roller_[gp];
  for (std::size_t c = 0; c < 3; ++c)
    if (fixed_[gp][c]) v[Eigen::Index(c)] = 0.0;
  return v;
}

int Solver::thread_count() const {
#ifdef _OPENMP
  return settings_.threads > 0 ? settings_.threads : omp_get_max_threads();
#else
  return 1;
#endif
}

std::optional<std::string> Solver::unstable_step_reason(double dt) const {
  // The reply to configure announces critical_timestep() as dt_max; allow for its round trip through JSON.
  if (settings_.mass_scaling || dt <= critical_timestep_ * (1.0 + 1e-12)) return std::nullopt;
  return "time step dt = " + format_seconds(dt) + " exceeds the critical step " + format_seconds(critical_timestep_) +
         " of the FDM grid (docs/theory/fdm.md §1.10: min V/(Cp A_max)/2) and mass scaling is off; use dt <= " +
         format_seconds(critical_timestep_) + " or set \"mass_scaling\": true";
}

void Solver::step(double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw SolverError("the FDM time step must be a positive finite number of seconds");
  if (const auto reason = unstable_step_reason(dt)) throw SolverError(*reason);
  update_inertial_masses(dt);
  gridpoint_pass(dt);
  zone_pass(dt);
  ++step_count_;
  work_progress::advance();  // the heartbeat's proof that the main thread works (SPEC.md §9.1)
  check_finite();
}

void Solver::gridpoint_pass(double dt) {
  const auto n_gp = std::ptrdiff_t(mesh_.gridpoint_count());
  const double alpha = settings_.local_damping;
#pragma omp parallel for num_threads(thread_count()) schedule(static) if (n_gp >= kMinParallelItems)
  for (std::ptrdiff_t i = 0; i < n_gp; ++i) {
    const auto gp = Index(i);
    const GridpointForces forces = gridpoint_forces(gp);
    // Only the free degrees of freedom are out of balance; a held component
    // carries a reaction. The reaction must not enter the damping either: on a
    // radial roller α|F_reaction| would leak into the tangential components and
    // make the free velocity chatter.
    const Vec3 free_force = prescribed_[gp] ? Vec3(Vec3::Zero()) : constrained(gp, forces.net);
    unbalanced_magnitude_[gp] = free_force.norm();  // §1.11
    reaction_[gp] = free_force - forces.net;
    applied_magnitude_[gp] = forces.magnitude;

    Vec3& v = velocity_[gp];
    Vec3 damped = free_force;
    // §1.9: F − α|F|sgn(v) per component, v = previous half-step velocity.
    for (Eigen::Index c = 0; c < 3; ++c) damped[c] -= alpha * std::abs(damped[c]) * sign(v[c]);
    v += (dt / inertial_mass_[gp]) * damped;  // §1.8
    v = constrained(gp, prescribed_[gp] ? prescribed_velocity_[gp] : v);
    displacement_[gp] += dt * v;
  }

  // Sums in gridpoint order, outside the parallel loop: deterministic.
  double unbalanced = 0.0;
  double applied = 0.0;
  double kinetic = 0.0;
  Vec3 reaction = Vec3::Zero();
  for (std::size_t gp = 0; gp < velocity_.size(); ++gp) {
    reaction += reaction_[gp];
    unbalanced += unbalanced_magnitude_[gp];
    applied += applied_magnitude_[gp];
    kinetic += 0.5 * real_mass_[gp] * velocity_[gp].squaredNorm();
  }
  // §1.11 "average" ratio: mean unbalanced force magnitude / mean applied force
  // magnitude over all gridpoints. The applied force at a gridpoint is taken as
  // Σ|tetrahedron force| + |gravity| + |face load| + |external force| (the
  // reference's inference; FLAC3D's exact definition is not documented).
  unbalanced_force_ratio_ = applied > 0.0 ? unbalanced / applied : 0.0;
  kinetic_energy_ = kinetic;
  support_reaction_ = reaction;
}

Vec3 Solver::total_body_force() const {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& f : body_force_) sum += f;
  return sum;
}

void Solver::zone_pass(double dt) {
  const auto n_zones = std::ptrdiff_t(mesh_.zone_count());
  const std::size_t state_size = material_.model->state_size();
  const constitutive::ConstitutiveModel& model = *material_.model;
  const bool average_mean_stress = model.needs_mean_stress_averaging();
#pragma omp parallel for num_threads(thread_count()) schedule(static) if (n_zones >= kMinParallelItems)
  for (std::ptrdiff_t z = 0; z < n_zones; ++z) {
    const Index first = Index(z) * kTetrahedraPerZone;
    std::array<SymTensor, kTetrahedraPerZone> rates;
    std::array<double, kTetrahedraPerZone> volumes{};
    for (Index t = 0; t < kTetrahedraPerZone; ++t) {
      rates[t] = strain_rate(tetrahedra_[first + t], velocity_);  // §1.4
      volumes[t] = tetrahedra_[first + t].volume;
    }
    apply_mixed_discretization(rates, volumes);  // §1.5
    std::array<double, kTetrahedraPerZone> old_means{};
    for (Index t = 0; t < kTetrahedraPerZone; ++t) {
      const Index tet = first + t;
      old_means[t] = stress_[tet].trace() / 3.0;
      model.update(constitutive::StrainIncrement{rates[t] * dt}, stress_[tet], constitutive::StateSpan(model_state_).subspan(tet * state_size, state_size));  // §1.6
    }
    const std::span<Stress> zone_stresses(stress_.data() + first, kTetrahedraPerZone);
    if (average_mean_stress) apply_mean_stress_mixed_discretization(zone_stresses, old_means, volumes);  // §1.5, stress pass
    for (Index t = 0; t < kTetrahedraPerZone; ++t) compute_tetrahedron_forces(first + t);
  }
}

void Solver::compute_tetrahedron_forces(Index tet) {
  const std::array<Vec3, 4> forces = nodal_forces(tetrahedra_[tet], stress_[tet]);  // §1.7
  for (std::size_t n = 0; n < 4; ++n) tet_force_[tet][n] = kOverlayWeight * forces[n];
}

void Solver::check_finite() const {
  if (std::isfinite(kinetic_energy_)) return;
  for (std::size_t gp = 0; gp < velocity_.size(); ++gp)
    if (!velocity_[gp].allFinite()) {
      const Vec3& x = mesh_.points[gp];
      std::ostringstream where;
      where << "gridpoint " << gp << " at (" << x.x() << ", " << x.y() << ", " << x.z() << ") m";
      throw SolverError("the FDM solution became non-finite at step " + std::to_string(step_count_) + " (" + where.str() +
                        "); check the loads, the material and the time step");
    }
  throw SolverError("the FDM kinetic energy became non-finite at step " + std::to_string(step_count_));
}

}  // namespace dfc::fdm
