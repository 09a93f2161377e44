#include "dfc/continuum/axisymmetric_solver.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <map>
#include <set>

#include "dfc/continuum/boundary_edges.hpp"
#include "dfc/continuum/containing_triangles.hpp"
#include "dfc/continuum/delaunay_retriangulation.hpp"
#include "dfc/continuum/nodal_average.hpp"

namespace dfc::continuum {

namespace {

NodalVectors gather(const std::vector<Point>& values, const Triangle& triangle) {
  return {values[triangle[0]], values[triangle[1]], values[triangle[2]]};
}

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

RemeshReport AxisymmetricSolver::remesh(double minimum_angle_deg) {
  RemeshReport report;
  report.triangles_before = mesh_.triangles.size();
  report.mass_before = total_mass();
  const Index node_count = mesh_.nodes.size();
  const std::vector<Triangle>& old_triangles = mesh_.triangles;
  const std::vector<Edge> boundary = boundary_edges(old_triangles);
  Retriangulation retriangulation = delaunay_retriangulation(mesh_.nodes, boundary, minimum_angle_deg);
  const std::vector<Interpolation> added_from = add_nodes(retriangulation, boundary);
  report.nodes_added = retriangulation.added_nodes.size();
  std::vector<Triangle> triangles = std::move(retriangulation.triangles);

  // Per component (the 6 stress components, the model's history, the
  // density) the old triangles' values and the field recovered from them at
  // the nodes (volume-weighted means; docs/continuum_pile.md §5).
  std::vector<double> old_volumes;
  for (const Triangle& t : old_triangles) old_volumes.push_back(triangle_geometry(gather(mesh_.nodes, t)).volume());
  const std::size_t state_size = model_->state_size();
  const std::size_t components = 6 + state_size + 1;
  std::vector<std::vector<double>> old_values(components, std::vector<double>(old_triangles.size()));
  std::vector<std::vector<double>> nodal(components);
  for (std::size_t c = 0; c < components; ++c) {
    for (Index t = 0; t < old_triangles.size(); ++t) {
      if (c < 6) old_values[c][t] = stresses_[t].components()[c];
      else if (c < 6 + state_size) old_values[c][t] = model_state_[t * state_size + (c - 6)];
      else old_values[c][t] = triangle_masses_[t] / old_volumes[t];
    }
    nodal[c] = nodal_means(old_triangles, node_count, old_volumes, old_values[c]);
    // At the added nodes: the recovered field interpolated in the old mesh.
    for (const Interpolation& from : added_from) {
      const Triangle& host = old_triangles[from.triangle];
      nodal[c].push_back(from.weights[0] * nodal[c][host[0]] + from.weights[1] * nodal[c][host[1]] + from.weights[2] * nodal[c][host[2]]);
    }
  }
  const auto recovered_at_centroid = [&](const Triangle& tri, std::size_t c) {
    return (nodal[c][tri[0]] + nodal[c][tri[1]] + nodal[c][tri[2]]) / 3.0;
  };

  std::vector<Point> centroids;
  for (const Triangle& tri : triangles) centroids.push_back((mesh_.nodes[tri[0]] + mesh_.nodes[tri[1]] + mesh_.nodes[tri[2]]) / 3.0);
  const std::vector<Index> source = containing_triangles(mesh_.nodes, old_triangles, centroids);
  std::set<Triangle> old_set;
  for (Triangle key : old_triangles) {
    std::sort(key.begin(), key.end());
    old_set.insert(key);
  }
  std::vector<Stress> stresses;
  std::vector<double> model_state;
  std::vector<double> areas;
  std::vector<double> masses;
  for (Index t = 0; t < triangles.size(); ++t) {
    const Triangle& tri = triangles[t];
    const TriangleGeometry g = triangle_geometry(gather(mesh_.nodes, tri));
    areas.push_back(g.area);
    Triangle key = tri;
    std::sort(key.begin(), key.end());
    if (!old_set.contains(key)) ++report.triangles_changed;
    // The old triangle's own value, corrected by the change of the recovered
    // field between its centroid and the new one: a kept triangle keeps its
    // state exactly, a smooth field is carried to second order, and the
    // state is not smeared over a nodal patch (docs/continuum_pile.md §5).
    const Index old = source[t];
    const auto transferred = [&](std::size_t c) {
      return old_values[c][old] + recovered_at_centroid(tri, c) - recovered_at_centroid(old_triangles[old], c);
    };
    stresses.push_back({transferred(0), transferred(1), transferred(2), transferred(3), transferred(4), transferred(5)});
    for (std::size_t s = 0; s < state_size; ++s) model_state.push_back(transferred(6 + s));
    masses.push_back(transferred(6 + state_size) * g.volume());
  }
  double transferred = 0.0;
  for (const double m : masses) transferred += m;
  report.mass_transferred = transferred;
  // The same nodes and boundary enclose the same volume, so the transferred
  // densities miss the mass only by the smoothing of the density; one factor
  // restores it exactly.
  for (double& m : masses) m *= report.mass_before / transferred;

  mesh_.triangles = std::move(triangles);
  stresses_ = std::move(stresses);
  model_state_ = std::move(model_state);
  initial_areas_ = std::move(areas);
  triangle_masses_ = std::move(masses);
  report.triangles_after = mesh_.triangles.size();
  compute_forces_and_masses();
  unbalanced_force_ratio_ = measure_unbalanced_force_ratio();
  return report;
}

std::vector<AxisymmetricSolver::Interpolation> AxisymmetricSolver::add_nodes(const Retriangulation& retriangulation,
                                                                              std::span<const Edge> boundary) {
  const Index first_added = mesh_.nodes.size();
  const std::vector<Index> hosts = containing_triangles(mesh_.nodes, mesh_.triangles, retriangulation.added_nodes);
  std::vector<Interpolation> interpolations;
  // Added nodes on each split boundary edge, ordered from its first node.
  std::map<Edge, std::vector<std::pair<double, Index>>> splits;
  for (Index k = 0; k < retriangulation.added_nodes.size(); ++k) {
    const Index node = first_added + k;
    const Point& p = retriangulation.added_nodes[k];
    // Velocity: the old mesh's linear field at the new node.
    const Triangle& host = mesh_.triangles[hosts[k]];
    const auto weights = barycentric_coordinates(p, mesh_.nodes[host[0]], mesh_.nodes[host[1]], mesh_.nodes[host[2]]);
    interpolations.push_back({hosts[k], weights});
    Point velocity = Point::Zero();
    for (int i = 0; i < 3; ++i) velocity += weights[i] * velocities_[host[i]];
    std::array<bool, 2> prescribed{false, false};
    Point prescribed_velocity = Point::Zero();
    const Index edge = retriangulation.boundary_edge_of_added[k];
    if (edge != Retriangulation::kInterior) {
      // A node on a boundary edge inherits what both ends share: a velocity
      // component prescribed at both (interpolated), and their named groups.
      const Index a = boundary[edge][0];
      const Index b = boundary[edge][1];
      const double along = (p - mesh_.nodes[a]).norm() / (mesh_.nodes[b] - mesh_.nodes[a]).norm();
      for (std::size_t axis = 0; axis < 2; ++axis) {
        if (!(prescribed_[a][axis] && prescribed_[b][axis])) continue;
        const auto component = static_cast<Eigen::Index>(axis);
        prescribed[axis] = true;
        prescribed_velocity[component] =
            (1.0 - along) * prescribed_velocities_[a][component] + along * prescribed_velocities_[b][component];
        velocity[component] = prescribed_velocity[component];
      }
      for (auto& [name, group] : mesh_.node_groups)
        if (std::find(group.begin(), group.end(), a) != group.end() && std::find(group.begin(), group.end(), b) != group.end())
          group.push_back(node);
      splits[boundary[edge]].emplace_back(along, node);
    }
    mesh_.nodes.push_back(p);
    velocities_.push_back(velocity);
    prescribed_.push_back(prescribed);
    prescribed_velocities_.push_back(prescribed_velocity);
  }
  for (auto& [name, edges] : mesh_.edge_groups) {
    std::vector<Edge> split_edges;
    for (const Edge& e : edges) {
      auto found = splits.find(e);
      if (found == splits.end()) {
        split_edges.push_back(e);
        continue;
      }
      std::sort(found->second.begin(), found->second.end());
      Index from = e[0];
      for (const auto& [along, node] : found->second) {
        split_edges.push_back({from, node});
        from = node;
      }
      split_edges.push_back({from, e[1]});
    }
    edges = std::move(split_edges);
  }
  const Index nodes = mesh_.nodes.size();
  masses_.resize(nodes, 0.0);
  internal_forces_.resize(nodes, Point::Zero());
  external_forces_.resize(nodes, Point::Zero());
  return interpolations;
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
