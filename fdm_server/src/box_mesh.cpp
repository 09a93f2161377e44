// Box generator: a (graded) lattice of (nx+1)(ny+1)(nz+1) gridpoints.
#include "dfc/common/errors.hpp"
#include "dfc/fdm/grading.hpp"
#include "dfc/fdm/mesh_generators.hpp"
#include "structured_mesh.hpp"

namespace dfc::fdm {

Mesh make_box(const BoxSpec& spec) {
  const auto [nx, ny, nz] = spec.zones;
  if (nx < 1 || ny < 1 || nz < 1) throw UserError("box: every zone count must be >= 1");
  if (!(spec.size.minCoeff() > 0.0)) throw UserError("box: every size must be > 0");
  for (const double g : spec.grading)
    if (!(g > 0.0)) throw UserError("box: every grading ratio must be > 0");

  std::array<std::vector<double>, 3> ticks;
  for (std::size_t a = 0; a < 3; ++a) {
    const auto axis = Eigen::Index(a);
    // Both ends exact, so opposite faces are exactly planar.
    ticks[a] = geometric_spacing(spec.origin[axis], spec.origin[axis] + spec.size[axis], spec.zones[a], spec.grading[a]);
  }
  Mesh mesh;
  mesh.points.reserve((nx + 1) * (ny + 1) * (nz + 1));
  for (Index k = 0; k <= nz; ++k)
    for (Index j = 0; j <= ny; ++j)
      for (Index i = 0; i <= nx; ++i) mesh.points.emplace_back(ticks[0][i], ticks[1][j], ticks[2][k]);

  const std::array<Index, 3> counts = spec.zones;
  const detail::LatticeNodeIndex node = [nx = nx, ny = ny](Index i, Index j, Index k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  detail::add_lattice_zones(mesh, counts, node);
  detail::add_lattice_face_group(mesh, "xmin", counts, node, 0, 0);
  detail::add_lattice_face_group(mesh, "xmax", counts, node, 0, 1);
  detail::add_lattice_face_group(mesh, "ymin", counts, node, 1, 0);
  detail::add_lattice_face_group(mesh, "ymax", counts, node, 1, 1);
  detail::add_lattice_face_group(mesh, "zmin", counts, node, 2, 0);
  detail::add_lattice_face_group(mesh, "zmax", counts, node, 2, 1);
  return mesh;
}

}  // namespace dfc::fdm
