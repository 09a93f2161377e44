#include "dfc/continuum/pile_mesh.hpp"

#include <algorithm>
#include <cassert>
#include <utility>

#include "dfc/continuum/mapped_grid.hpp"
#include "dfc/fdm/grading.hpp"

namespace dfc::continuum {

namespace {

/// geometric_spacing from `fine` to `coarse`, returned in increasing order.
std::vector<double> ascending(double fine, double coarse, Index n, double ratio) {
  std::vector<double> values = fdm::geometric_spacing(fine, coarse, n, ratio);
  if (fine > coarse) std::reverse(values.begin(), values.end());
  return values;
}

}  // namespace

AxisymmetricMesh pile_mesh(const PileMeshSpec& spec) {
  assert(spec.pile_inner_radius >= 0.0 && spec.pile_outer_radius > spec.pile_inner_radius && spec.radius > spec.pile_outer_radius);
  std::vector<double> radii;
  if (spec.pile_inner_radius > 0.0) radii = ascending(spec.pile_inner_radius, 0.0, spec.bore_divisions, spec.radial_ratio);
  const std::vector<double> wall = fdm::geometric_spacing(spec.pile_inner_radius, spec.pile_outer_radius, spec.wall_divisions, 1.0);
  radii.insert(radii.end(), wall.begin() + (radii.empty() ? 0 : 1), wall.end());
  const std::vector<double> outside = ascending(spec.pile_outer_radius, spec.radius, spec.outside_divisions, spec.radial_ratio);
  radii.insert(radii.end(), outside.begin() + 1, outside.end());
  const std::vector<double> levels = ascending(spec.height, 0.0, spec.vertical_divisions, spec.vertical_ratio);
  AxisymmetricMesh mesh = mapped_grid(radii, levels, [](double r, double z) { return Point(r, z); }, "bottom", "top");
  // The first column is the axis.
  mesh.node_groups["axis"] = std::move(mesh.node_groups["inner"]);
  mesh.edge_groups["axis"] = std::move(mesh.edge_groups["inner"]);
  mesh.node_groups.erase("inner");
  mesh.edge_groups.erase("inner");
  return mesh;
}

}  // namespace dfc::continuum
