#include "dfc/continuum/strip_mesh.hpp"

#include "dfc/fdm/grading.hpp"

namespace dfc::continuum {

AxisymmetricMesh strip_mesh(const StripMeshSpec& spec) {
  const std::vector<double> radii = fdm::geometric_spacing(spec.inner_radius, spec.outer_radius, spec.radial_divisions, spec.radial_ratio);
  const std::vector<double> levels = fdm::geometric_spacing(0.0, spec.height, spec.vertical_divisions, 1.0);
  const Index columns = radii.size();
  const auto node = [columns](Index i, Index j) { return j * columns + i; };

  AxisymmetricMesh mesh;
  for (const double z : levels)
    for (const double r : radii) mesh.nodes.emplace_back(r, z);
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
  auto& bottom = mesh.node_groups["bottom"];
  auto& top = mesh.node_groups["top"];
  for (Index i = 0; i < columns; ++i) {
    bottom.push_back(node(i, 0));
    top.push_back(node(i, levels.size() - 1));
  }
  // Body on the left: downwards along the cavity wall, upwards along the outer wall.
  auto& inner_edges = mesh.edge_groups["inner"];
  auto& outer_edges = mesh.edge_groups["outer"];
  for (Index j = 0; j + 1 < levels.size(); ++j) {
    inner_edges.push_back({node(0, j + 1), node(0, j)});
    outer_edges.push_back({node(columns - 1, j), node(columns - 1, j + 1)});
  }
  return mesh;
}

}  // namespace dfc::continuum
