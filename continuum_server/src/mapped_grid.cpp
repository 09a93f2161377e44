#include "dfc/continuum/mapped_grid.hpp"

namespace dfc::continuum {

AxisymmetricMesh mapped_grid(const std::vector<double>& radii, const std::vector<double>& levels,
                             const std::function<Point(double, double)>& place, const std::string& first_side,
                             const std::string& last_side) {
  const Index columns = radii.size();
  const auto node = [columns](Index i, Index j) { return j * columns + i; };
  AxisymmetricMesh mesh;
  for (const double level : levels)
    for (const double radius : radii) mesh.nodes.push_back(place(radius, level));
  for (Index j = 0; j + 1 < levels.size(); ++j) {
    for (Index i = 0; i + 1 < columns; ++i) {
      const Index n00 = node(i, j), n10 = node(i + 1, j), n11 = node(i + 1, j + 1), n01 = node(i, j + 1);
      if ((i + j) % 2 == 0) {
        mesh.triangles.push_back({n00, n10, n11});
        mesh.triangles.push_back({n00, n11, n01});
      } else {
        mesh.triangles.push_back({n00, n10, n01});
        mesh.triangles.push_back({n10, n11, n01});
      }
    }
  }
  auto& inner = mesh.node_groups["inner"];
  auto& outer = mesh.node_groups["outer"];
  for (Index j = 0; j < levels.size(); ++j) {
    inner.push_back(node(0, j));
    outer.push_back(node(columns - 1, j));
  }
  auto& first = mesh.node_groups[first_side];
  auto& last = mesh.node_groups[last_side];
  for (Index i = 0; i < columns; ++i) {
    first.push_back(node(i, 0));
    last.push_back(node(i, levels.size() - 1));
  }
  // Body on the left: along i on the first side, against i on the last.
  auto& first_edges = mesh.edge_groups[first_side];
  auto& last_edges = mesh.edge_groups[last_side];
  for (Index i = 0; i + 1 < columns; ++i) {
    first_edges.push_back({node(i, 0), node(i + 1, 0)});
    last_edges.push_back({node(i + 1, levels.size() - 1), node(i, levels.size() - 1)});
  }
  // Body on the left: against j along the cavity wall, along j on the outer wall.
  auto& inner_edges = mesh.edge_groups["inner"];
  auto& outer_edges = mesh.edge_groups["outer"];
  for (Index j = 0; j + 1 < levels.size(); ++j) {
    inner_edges.push_back({node(0, j + 1), node(0, j)});
    outer_edges.push_back({node(columns - 1, j), node(columns - 1, j + 1)});
  }
  return mesh;
}

}  // namespace dfc::continuum
