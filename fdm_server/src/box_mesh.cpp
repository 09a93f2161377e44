// Box generator: a regular lattice of (nx+1)(ny+1)(nz+1) gridpoints.
#include "dfc/common/errors.hpp"
#include "dfc/fdm/mesh_generators.hpp"
#include "structured_mesh.hpp"

namespace dfc::fdm {

Mesh make_box(const BoxSpec& spec) {
  const auto [nx, ny, nz] = spec.zones;
  if (nx < 1 || ny < 1 || nz < 1) throw UserError("box: every zone count must be >= 1");
  if (!(spec.size.minCoeff() > 0.0)) throw UserError("box: every size must be > 0");

  Mesh mesh;
  mesh.points.reserve((nx + 1) * (ny + 1) * (nz + 1));
  for (Index k = 0; k <= nz; ++k)
    for (Index j = 0; j <= ny; ++j)
      for (Index i = 0; i <= nx; ++i) {
        // Fractions i/n are exact at both ends, so opposite faces are exactly planar.
        const Vec3 fraction(double(i) / double(nx), double(j) / double(ny), double(k) / double(nz));
        mesh.points.push_back(spec.origin + spec.size.cwiseProduct(fraction));
      }

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
