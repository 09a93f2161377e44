#include "dfc/reference/elastic_reference_backend.hpp"

#include <array>
#include <string>

#include "dfc/common/errors.hpp"
#include "dfc/common/version.hpp"
#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/fdm/grid_snapshot.hpp"
#include "dfc/fdm/hex_overlays.hpp"
#include "dfc/fdm/mixed_discretization.hpp"
#include "dfc/fdm/provider_interface.hpp"
#include "dfc/protocol/monitor_units.hpp"

namespace dfc::reference {

namespace {

using fdm::Index;
using fdm::Stress;
using fdm::Vec3;
using protocol::Array;
using protocol::ErrorCode;
using protocol::ProtocolError;

constexpr const char* kName = "elastic_reference_server";

nlohmann::json to_json(const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

/// Zone stresses of the static state: initial stress plus the elastic
/// increment of the displacement field, with the same mixed discretization
/// and volume average as the explicit solver (docs/theory/fdm.md §1.5, §1.6).
std::vector<Stress> zone_stresses(const fdm::Solver& solver, std::span<const Vec3> displacement) {
  const constitutive::ElasticModuli moduli = solver.model().stiffest_moduli();
  std::vector<Stress> out(solver.mesh().zone_count());
  for (Index zone = 0; zone < out.size(); ++zone) {
    const Index first = zone * fdm::kTetrahedraPerZone;
    std::array<fdm::SymTensor, fdm::kTetrahedraPerZone> strains;
    std::array<double, fdm::kTetrahedraPerZone> volumes{};
    for (Index t = 0; t < fdm::kTetrahedraPerZone; ++t) {
      // The strain operator is linear: applied to displacements it gives strains (§1.4).
      strains[t] = fdm::strain_rate(solver.tetrahedra()[first + t], displacement);
      volumes[t] = solver.tetrahedra()[first + t].volume;
    }
    fdm::apply_mixed_discretization(strains, volumes);
    Stress sum;
    double volume = 0.0;
    for (Index t = 0; t < fdm::kTetrahedraPerZone; ++t) {
      sum += (solver.tetrahedron_stresses()[first + t] + constitutive::elastic_stress_increment(moduli, strains[t])) * volumes[t];
      volume += volumes[t];
    }
    out[zone] = sum * (1.0 / volume);
  }
  return out;
}

}  // namespace

protocol::SolverIdentity ElasticReferenceBackend::identity() const {
  return {kName, std::string(project_version()), "continuum", {protocol::capability::provides_interface, protocol::capability::snapshot}};
}

const fdm::FdmModel& ElasticReferenceBackend::model() const {
  if (!model_ || !condensed_) throw ProtocolError(ErrorCode::out_of_order, std::string(kName) + " is not configured yet; send configure first");
  return *model_;
}

const CondensedElasticContinuum& ElasticReferenceBackend::condensed() const {
  (void)model();
  return *condensed_;
}

nlohmann::json ElasticReferenceBackend::configure(const nlohmann::json& section) {
  condensed_.reset();
  model_.emplace(fdm::load_fdm_model(section));
  const fdm::Solver& solver = model_->solver;
  if (solver.model().keyword() != constitutive::ElasticModel::kKeyword)
    throw ConfigError("material.model", "the elastic reference continuum solves linear elasticity only, got \"" +
                                            std::string(solver.model().keyword()) +
                                            "\"; set material.model to \"elastic\" (or run this section with fdm_server)");
  if (model_->coupling.role != fdm::CouplingRole::provider)
    throw ConfigError("coupling.role", std::string(kName) +
                                           " only provides the interface; set coupling.role to \"provider\" with the coupling face group");
  try {
    condensed_.emplace(solver, solver.mesh().face_group_gridpoints(model_->coupling.group));
  } catch (const UserError& e) {
    throw ConfigError("boundaries", e.what());
  }
  const std::size_t rows = condensed_->interface_gridpoints().size();
  interface_force_.assign(3 * rows, 0.0);
  interface_displacement_ = Eigen::VectorXd::Zero(Eigen::Index(3 * rows));
  step_ = 0;
  interface_force_sum_ = Vec3::Zero();
  interface_power_ = 0.0;
  // A static solve is stable for any Δt; the FDM's critical step is only a
  // sensible default for a run with no DEM partner to set the pace.
  return {{"dt_suggested", solver.critical_timestep()},
          {"dt_max", nullptr},
          {"gridpoints", solver.mesh().gridpoint_count()},
          {"zones", solver.mesh().zone_count()},
          {"coupling_role", "provider"},
          {"interface_nodes", rows},
          {"capabilities", identity().capabilities},
          {protocol::monitor_units_key, protocol::shared_monitor_units()}};
}

protocol::InterfaceMesh ElasticReferenceBackend::interface_mesh() {
  const fdm::FdmModel& m = model();
  return fdm::provider_interface_mesh(m.solver.mesh(), condensed_->interface_gridpoints(), m.coupling.group);
}

protocol::AdvanceResult ElasticReferenceBackend::advance(const protocol::AdvanceRequest& request) {
  (void)model();
  const auto n = std::int64_t(condensed_->interface_gridpoints().size());
  // `mass` is validated and ignored: a static solve has no inertia to add it to.
  interface_force_ = fdm::read_provider_inputs(request.inputs, n, std::string("the provider ") + kName).force;
  const Eigen::VectorXd displacement = condensed_->interface_displacement(interface_force_);
  const Eigen::VectorXd velocity = (displacement - interface_displacement_) / (double(request.n_steps) * request.dt);
  interface_displacement_ = displacement;
  step_ += request.n_steps;

  // Power of the received forces with the velocity over the advance; summed in node order (deterministic).
  interface_force_sum_ = Vec3::Zero();
  interface_power_ = 0.0;
  for (std::int64_t r = 0; r < n; ++r) {
    const Vec3 force(interface_force_[std::size_t(3 * r)], interface_force_[std::size_t(3 * r + 1)], interface_force_[std::size_t(3 * r + 2)]);
    interface_force_sum_ += force;
    interface_power_ += force.dot(velocity.segment<3>(3 * r));
  }
  protocol::AdvanceResult result;
  result.outputs.push_back(Array::from_f64(protocol::field::velocity, {n, 3}, std::vector<double>(velocity.begin(), velocity.end())));
  result.outputs.push_back(
      Array::from_f64(protocol::field::displacement, {n, 3}, std::vector<double>(displacement.begin(), displacement.end())));
  result.monitors = monitors();
  return result;
}

nlohmann::json ElasticReferenceBackend::monitors() {
  // Every state it reports is an exact static equilibrium: no out-of-balance force, no motion energy.
  return {{"unbalanced_force_ratio", 0.0},
          {"kinetic_energy_j", 0.0},
          {"step", step_},
          {"interface_force_received", to_json(interface_force_sum_)},
          {"interface_power_w", interface_power_}};
}

std::vector<protocol::Array> ElasticReferenceBackend::snapshot(std::string& kind) {
  const fdm::Solver& solver = model().solver;
  kind = "grid";
  const std::vector<Vec3> displacement = condensed_->displacement_field(interface_force_);
  // Quasi-static: the body has no velocity field of its own between equilibria.
  const std::vector<Vec3> velocity(displacement.size(), Vec3::Zero());
  return fdm::grid_snapshot(solver.mesh(), displacement, velocity, zone_stresses(solver, displacement));
}

}  // namespace dfc::reference
