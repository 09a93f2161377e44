#include "dfc/continuum/cavity_meshes.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "dfc/continuum/mapped_grid.hpp"
#include "dfc/fdm/grading.hpp"

namespace dfc::continuum {

namespace {

std::vector<double> graded_radii(const CavityMeshSpec& spec) {
  return fdm::geometric_spacing(spec.inner_radius, spec.outer_radius, spec.radial_divisions, spec.radial_ratio);
}

}  // namespace

AxisymmetricMesh strip_mesh(const CavityMeshSpec& spec) {
  const std::vector<double> levels = fdm::geometric_spacing(0.0, spec.strip_height, spec.tangential_divisions, 1.0);
  return mapped_grid(graded_radii(spec), levels, [](double r, double z) { return Point(r, z); }, "bottom", "top");
}

AxisymmetricMesh quarter_annulus_mesh(const CavityMeshSpec& spec) {
  std::vector<double> angles = fdm::geometric_spacing(0.0, 0.5 * std::numbers::pi, spec.tangential_divisions, 1.0);
  AxisymmetricMesh mesh = mapped_grid(
      graded_radii(spec), angles, [](double rho, double theta) { return Point(rho * std::cos(theta), rho * std::sin(theta)); },
      "equator", "axis");
  // cos(π/2) is 6e-17, not 0: put the axis nodes exactly on r = 0.
  for (const Index n : mesh.node_groups["axis"]) mesh.nodes[n].x() = 0.0;
  return mesh;
}

}  // namespace dfc::continuum
