// AxisymmetricSolver's remeshing and state transfer (docs/continuum_pile.md
// §4–§5); the time step is in axisymmetric_solver.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "dfc/continuum/axisymmetric_solver.hpp"
#include "dfc/continuum/boundary_edges.hpp"
#include "dfc/continuum/containing_triangles.hpp"
#include "dfc/continuum/equilibrium_correction.hpp"
#include "dfc/continuum/nodal_average.hpp"

namespace dfc::continuum {

namespace {

// The equilibrium restored after a remesh (docs/continuum_pile.md §5): the
// nodal force mismatch is corrected, in alternation with the model's return
// to its yield surface, until it is below 1e-6 of the norm of the internal
// forces (1e-3 N on the small pile model, whose force is 870 N).
constexpr double kEquilibriumTolerance = 1e-6;
// The alternation converges linearly (measured on the small pile: about 1.2 %
// of the mismatch less per iteration, 0.1 % of the pile force left after
// 200); each iteration is one back-substitution and one zero-strain update
// per adjusted triangle.
constexpr int kMaxEquilibriumIterations = 2000;

}  // namespace

RemeshReport AxisymmetricSolver::remesh(double minimum_angle_deg) {
  RemeshReport report;
  report.triangles_before = mesh_.triangles.size();
  report.mass_before = total_mass();
  const Index node_count = mesh_.nodes.size();
  // Each node's out-of-balance force without the pile's contact (found anew
  // each step), on the current state (a pore pressure may have been
  // prescribed since the last step): the remesh is to leave it as it was
  // (docs/continuum_pile.md §5).
  compute_forces_and_masses();
  std::vector<Point> unbalanced_before(node_count);
  for (Index n = 0; n < node_count; ++n) unbalanced_before[n] = external_forces_[n] - internal_forces_[n];
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
  // Per component and node, the range of the old triangles' values around it.
  // The corrected value below is limited to the range around its source
  // triangle, so the transfer makes no new extremum (Barth & Jespersen's
  // 1989 limiter): at the tip's corners, where the field changes by an order
  // of magnitude across a triangle, the unlimited correction gave negative
  // p_s and p_t to the structured Cam clay.
  std::vector<std::vector<double>> nodal_low(components, std::vector<double>(node_count, std::numeric_limits<double>::infinity()));
  std::vector<std::vector<double>> nodal_high(components, std::vector<double>(node_count, -std::numeric_limits<double>::infinity()));
  for (std::size_t c = 0; c < components; ++c)
    for (Index t = 0; t < old_triangles.size(); ++t)
      for (const Index n : old_triangles[t]) {
        nodal_low[c][n] = std::min(nodal_low[c][n], old_values[c][t]);
        nodal_high[c][n] = std::max(nodal_high[c][n], old_values[c][t]);
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
    // field between its centroid and the new one and limited: a kept
    // triangle keeps its state exactly, a smooth field is carried to second
    // order, and the state is not smeared over a nodal patch
    // (docs/continuum_pile.md §5).
    const Index old = source[t];
    const auto transferred = [&](std::size_t c) {
      const double value = old_values[c][old] + recovered_at_centroid(tri, c) - recovered_at_centroid(old_triangles[old], c);
      const Triangle& from = old_triangles[old];
      const double low = std::min({nodal_low[c][from[0]], nodal_low[c][from[1]], nodal_low[c][from[2]]});
      const double high = std::max({nodal_high[c][from[0]], nodal_high[c][from[1]], nodal_high[c][from[2]]});
      return std::clamp(value, low, high);
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
  // A node added on a boundary edge that cuts a corner of the pile lies in
  // it: onto the nearest face, before the contact sees it.
  if (pile_)
    for (Index n = node_count; n < mesh_.nodes.size(); ++n) mesh_.nodes[n] = pile_->pushed_out(mesh_.nodes[n]);
  compute_forces_and_masses();
  // The new triangles and those that share a node with one: the triangles
  // whose stresses the equilibrium correction may change. The neighbours
  // give it room where the new triangles alone would have to leave their
  // yield surfaces to carry the old nodal forces.
  std::vector<bool> near_new(mesh_.nodes.size(), false);
  for (const Triangle& tri : mesh_.triangles) {
    Triangle key = tri;
    std::sort(key.begin(), key.end());
    if (!old_set.contains(key))
      for (const Index n : tri) near_new[n] = true;
  }
  std::vector<bool> adjustable(mesh_.triangles.size(), false);
  for (Index t = 0; t < mesh_.triangles.size(); ++t)
    for (const Index n : mesh_.triangles[t]) adjustable[t] = adjustable[t] || near_new[n];
  unbalanced_before.resize(mesh_.nodes.size(), Point::Zero());  // an added node: in equilibrium
  restore_equilibrium(unbalanced_before, std::move(adjustable), report);
  // The pile's contact forces of the last step (found anew at the next), so
  // that the ratio measures the new mesh's balance and not the pile's reaction.
  pile_contacts_.resize(mesh_.nodes.size());
  for (Index n = 0; n < mesh_.nodes.size(); ++n) external_forces_[n] += pile_contacts_[n].force;
  unbalanced_force_ratio_ = measure_unbalanced_force_ratio();
  return report;
}

void AxisymmetricSolver::restore_equilibrium(std::span<const Point> unbalanced_before, std::vector<bool> adjustable,
                                             RemeshReport& report) {
  // On the same nodes and boundary edges a support's nodal reaction, the
  // integral of its traction against the boundary's shape functions, is the
  // same on any triangulation, so it is kept as well; nodes added by a
  // refinement take a share of it, so after one the reactions are left free.
  const std::vector<std::array<bool, 2>> nothing_free(mesh_.nodes.size(), {false, false});
  const std::span<const std::array<bool, 2>> free_or_not =
      report.nodes_added > 0 ? std::span<const std::array<bool, 2>>(prescribed_) : std::span<const std::array<bool, 2>>(nothing_free);
  std::optional<NodalForceCorrection> correction(std::in_place, mesh_.nodes, mesh_.triangles, adjustable, free_or_not);
  // The transferred states, for a triangle whose corrected stress the model cannot return.
  const std::vector<Stress> transferred_stresses = stresses_;
  const std::vector<double> transferred_states = model_state_;
  const std::size_t state_size = model_->state_size();
  double scale = 0.0;
  for (const Point& f : internal_forces_) scale += f.squaredNorm();
  const double tolerance = kEquilibriumTolerance * std::sqrt(scale);
  std::vector<Point> change(mesh_.nodes.size());
  while (report.equilibrium_iterations < kMaxEquilibriumIterations) {
    for (Index n = 0; n < mesh_.nodes.size(); ++n) change[n] = external_forces_[n] - internal_forces_[n] - unbalanced_before[n];
    ++report.equilibrium_iterations;
    report.equilibrium_residual = correction->apply(change, stresses_);
    if (report.equilibrium_residual <= tolerance) break;
    // The corrected stresses may lie outside the yield surface: the model
    // returns them (its own relaxation at zero strain), and the next
    // correction carries what that took from the nodal forces elsewhere.
    // Where the return fails (a structured Cam clay whose surface has shrunk
    // to nearly a point, §6.5), the triangle gets its transferred state back
    // and is not corrected again.
    bool dropped = false;
    for (Index t = 0; t < mesh_.triangles.size(); ++t) {
      if (!adjustable[t] || admit_stress(t, stresses_[t])) continue;
      stresses_[t] = transferred_stresses[t];
      const auto from = transferred_states.begin() + std::ptrdiff_t(t * state_size);
      std::copy(from, from + std::ptrdiff_t(state_size), model_state_.begin() + std::ptrdiff_t(t * state_size));
      adjustable[t] = false;
      dropped = true;
    }
    if (dropped) correction.emplace(mesh_.nodes, mesh_.triangles, adjustable, free_or_not);
    compute_forces_and_masses();
  }
  compute_forces_and_masses();
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
    double pore_pressure = 0.0;
    for (int i = 0; i < 3; ++i) {
      velocity += weights[i] * velocities_[host[i]];
      pore_pressure += weights[i] * pore_pressures_[host[i]];
    }
    bool pore_pressure_prescribed = false;
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
      // A drained edge stays drained: its pressure interpolated between its ends.
      if (pore_pressure_prescribed_[a] && pore_pressure_prescribed_[b]) {
        pore_pressure_prescribed = true;
        pore_pressure = (1.0 - along) * pore_pressures_[a] + along * pore_pressures_[b];
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
    pore_pressures_.push_back(pore_pressure);
    pore_pressure_prescribed_.push_back(pore_pressure_prescribed);
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

}  // namespace dfc::continuum
