#include "dfc/continuum/continuum_backend.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <string>

#include "dfc/common/errors.hpp"
#include "dfc/common/version.hpp"
#include "dfc/protocol/monitor_units.hpp"
#include "dfc/protocol/progress_monitors.hpp"

namespace dfc::continuum {

namespace {

using protocol::Array;
using protocol::ErrorCode;
using protocol::ProtocolError;

}  // namespace

protocol::SolverIdentity ContinuumBackend::identity() const {
  return {"continuum_server", std::string(project_version()), "continuum", {protocol::capability::snapshot}};
}

PileModel& ContinuumBackend::model() {
  if (!model_) throw ProtocolError(ErrorCode::out_of_order, "continuum_server is not configured yet; send configure first");
  return *model_;
}

nlohmann::json ContinuumBackend::configure(const nlohmann::json& section) {
  model_.reset();
  model_.emplace(load_pile_model(section));
  const AxisymmetricSolver& solver = *model_->solver;
  reference_nodes_ = solver.mesh().nodes;
  bore_surface_.clear();
  for (const Index n : solver.mesh().node_group("top"))
    if (reference_nodes_[n].x() < solver.pile().spec().inner_radius) bore_surface_.push_back(n);
  peak_force_ = 0.0;
  remeshes_ = 0;
  nlohmann::json info = {{"dt_suggested", 1.0},
                         {"dt_max", nullptr},  // mass scaling: any step is stable (docs/continuum_pile.md §1)
                         {"nodes", solver.mesh().nodes.size()},
                         {"triangles", solver.mesh().triangles.size()},
                         {"capabilities", {protocol::capability::snapshot}}};
  nlohmann::json units = protocol::shared_monitor_units();
  for (const char* force : {"pile_force_n", "pile_peak_force_n", "pile_annulus_force_n", "pile_inner_shaft_force_n",
                            "pile_outer_shaft_force_n", "base_reaction_n"})
    units[force] = protocol::unit::newton;
  units["pile_displacement_m"] = protocol::unit::metre;
  units["pile_plug_length_m"] = protocol::unit::metre;
  for (const char* count : {"smallest_area_ratio", "smallest_angle_rad", "remeshes", "triangles"}) units[count] = protocol::unit::dimensionless;
  info[protocol::monitor_units_key] = units;
  info[protocol::progress_monitors_key] = protocol::to_json({{"pile_displacement_m", "pile", 1e3, "mm"},
                                                             {"pile_force_n", "force", 1.0, "N"},
                                                             {"pile_plug_length_m", "plug", 1e3, "mm"}});
  return info;
}

protocol::AdvanceResult ContinuumBackend::advance(const protocol::AdvanceRequest& request) {
  PileModel& m = model();
  protocol::require_only(request.inputs, {}, "continuum_server (a single-participant model, no interface)");
  dt_ = request.dt;
  RigidPile& pile = m.solver->pile();
  for (std::int64_t k = 0; k < request.n_steps; ++k) {
    // The pile stops on pile.depth_m exactly.
    const double left = m.stop_depth ? std::max(0.0, *m.stop_depth - pile.penetration()) : m.pile_step;
    pile.set_velocity(std::min(m.pile_step, left));
    try {
      m.solver->step();
    } catch (const std::runtime_error& e) {
      throw SolverError(std::string("continuum_server: ") + e.what());
    }
    // A sum over all nodes: any non-finite velocity makes it non-finite.
    if (!std::isfinite(m.solver->kinetic_energy()))
      throw SolverError("continuum_server: the solution diverged (non-finite velocities) at step " + std::to_string(m.solver->steps_taken()) +
                        "; lower pile.step_m or refine the mesh at the pile");
    peak_force_ = std::max(peak_force_, m.solver->pile_forces().total());
  }
  const double smallest = m.solver->smallest_area_ratio();
  if (!(smallest > 0.0))
    throw SolverError("continuum_server: a triangle inverted (smallest area ratio " + std::to_string(smallest) + ") by step " +
                      std::to_string(m.solver->steps_taken()) +
                      ": the mesh is too distorted for the penetration; refine the mesh at the pile, lower pile.step_m or set "
                      "mesh.remesh_below_area_ratio");
  if (m.remesh_below_area_ratio && smallest < *m.remesh_below_area_ratio) {
    const RemeshReport report = m.solver->remesh(m.remesh_refine_deg);
    ++remeshes_;
    // Each remesh in the server's log: how much changed and how well the
    // equilibrium correction converged (docs/continuum_pile.md §5).
    std::cerr << "continuum_server: remesh " << remeshes_ << " at step " << m.solver->steps_taken() << " (pile "
              << pile.penetration() * 1e3 << " mm): " << report.triangles_changed << " of " << report.triangles_after
              << " triangles new, " << report.nodes_added << " nodes added; equilibrium: " << report.equilibrium_iterations
              << " corrections, last mismatch " << report.equilibrium_residual << " N, unbalanced-force ratio "
              << m.solver->unbalanced_force_ratio() << "\n";
    // The added nodes: their reference position is where they were added.
    const std::vector<Point>& nodes = m.solver->mesh().nodes;
    reference_nodes_.insert(reference_nodes_.end(), nodes.begin() + std::ptrdiff_t(reference_nodes_.size()), nodes.end());
  }
  return {{}, monitors()};
}

double ContinuumBackend::plug_length() const {
  if (bore_surface_.empty()) return 0.0;
  double sum = 0.0;
  for (const Index n : bore_surface_) sum += model_->solver->mesh().nodes[n].y();
  return sum / double(bore_surface_.size()) - model_->solver->pile().tip();
}

nlohmann::json ContinuumBackend::monitors() {
  const AxisymmetricSolver& s = *model().solver;
  const PileForces forces = s.pile_forces();
  return {{"unbalanced_force_ratio", s.unbalanced_force_ratio()},
          {"kinetic_energy_j", s.kinetic_energy()},
          {"step", s.steps_taken()},
          {"pile_force_n", forces.total()},
          {"pile_peak_force_n", peak_force_},
          {"pile_annulus_force_n", forces.annulus},
          {"pile_inner_shaft_force_n", forces.inner_shaft},
          {"pile_outer_shaft_force_n", forces.outer_shaft},
          {"pile_displacement_m", s.pile().penetration()},
          {"pile_plug_length_m", plug_length()},
          // The base's force on the soil (its nodes' internal force; z up).
          {"base_reaction_n", s.internal_force_sum(s.mesh().node_group("bottom")).y()},
          {"smallest_area_ratio", s.smallest_area_ratio()},
          {"smallest_angle_rad", s.smallest_angle_deg() * std::numbers::pi / 180.0},
          {"remeshes", remeshes_},
          {"triangles", s.mesh().triangles.size()}};
}

std::vector<Array> ContinuumBackend::snapshot(std::string& kind) {
  const AxisymmetricSolver& s = *model().solver;
  kind = "grid";
  const AxisymmetricMesh& mesh = s.mesh();
  const auto n = std::int64_t(mesh.nodes.size());
  const auto t = std::int64_t(mesh.triangles.size());
  // The meridian plane y = 0: x = r.
  std::vector<double> position, displacement, velocity;
  for (Index i = 0; i < mesh.nodes.size(); ++i) {
    const Point& x0 = reference_nodes_[i];
    const Point u = mesh.nodes[i] - x0;
    const Point v = s.velocities()[i] / dt_;
    position.insert(position.end(), {x0.x(), 0.0, x0.y()});
    displacement.insert(displacement.end(), {u.x(), 0.0, u.y()});
    velocity.insert(velocity.end(), {v.x(), 0.0, v.y()});
  }
  std::vector<std::int64_t> triangle_nodes;
  std::vector<double> triangle_stress;
  for (Index k = 0; k < mesh.triangles.size(); ++k) {
    for (const Index node : mesh.triangles[k]) triangle_nodes.push_back(std::int64_t(node));
    // (xx, xy, xz, yy, yz, zz) with x = r, y = θ: σ_rθ = σ_θz = 0 (no torsion).
    const Stress& st = s.stresses()[k];
    triangle_stress.insert(triangle_stress.end(), {st.xx, 0.0, st.zx, st.yy, 0.0, st.zz});
  }
  return {Array::from_f64("node_position", {n, 3}, position), Array::from_f64("node_displacement", {n, 3}, displacement),
          Array::from_f64("node_velocity", {n, 3}, velocity), Array::from_i64("triangle_nodes", {t, 3}, triangle_nodes),
          Array::from_f64("triangle_stress", {t, 6}, triangle_stress)};
}

}  // namespace dfc::continuum
