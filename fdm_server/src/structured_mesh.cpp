#include "structured_mesh.hpp"

namespace dfc::fdm::detail {

namespace {

HexZone lattice_zone(const std::array<Index, 3>& cell, const LatticeNodeIndex& node) {
  HexZone zone{};
  for (std::size_t c = 0; c < 8; ++c) {
    const auto& o = kFlacCornerOffsets[c];
    zone[c] = node(cell[0] + Index(o[0]), cell[1] + Index(o[1]), cell[2] + Index(o[2]));
  }
  return zone;
}

}  // namespace

void add_lattice_zones(Mesh& mesh, const std::array<Index, 3>& counts, const LatticeNodeIndex& node) {
  mesh.zones.reserve(mesh.zones.size() + counts[0] * counts[1] * counts[2]);
  for (Index k = 0; k < counts[2]; ++k)
    for (Index j = 0; j < counts[1]; ++j)
      for (Index i = 0; i < counts[0]; ++i) mesh.zones.push_back(lattice_zone({i, j, k}, node));
}

void add_lattice_face_group(Mesh& mesh, const std::string& name, const std::array<Index, 3>& counts, const LatticeNodeIndex& node,
                            int axis, int side) {
  const auto a = std::size_t(axis);
  const std::size_t u = (a + 1) % 3;  // the two in-face lattice directions
  const std::size_t v = (a + 2) % 3;
  std::vector<FaceQuad>& faces = mesh.face_groups[name];
  std::array<Index, 3> extent = counts;
  extent[a] = 1;
  for (Index k = 0; k < extent[2]; ++k)
    for (Index j = 0; j < extent[1]; ++j)
      for (Index i = 0; i < extent[0]; ++i) {
        std::array<Index, 3> cell = {i, j, k};
        cell[a] = side == 0 ? 0 : counts[a] - 1;
        // Face corners in cyclic order around the face: (0,0), (1,0), (1,1), (0,1) in (u, v).
        FaceQuad face{};
        constexpr std::array<std::array<Index, 2>, 4> kCycle = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
        for (std::size_t c = 0; c < 4; ++c) {
          std::array<Index, 3> corner = cell;
          corner[a] += Index(side);
          corner[u] += kCycle[c][0];
          corner[v] += kCycle[c][1];
          face[c] = node(corner[0], corner[1], corner[2]);
        }
        // Orient outward: the vector area must point from the zone centroid to the face.
        Vec3 zone_centre = Vec3::Zero();
        for (const Index gp : lattice_zone(cell, node)) zone_centre += mesh.points[gp] / 8.0;
        if (quad_area_vector(mesh, face).dot(mesh.face_centroid(face) - zone_centre) < 0.0) std::swap(face[1], face[3]);
        faces.push_back(face);
      }
}

}  // namespace dfc::fdm::detail
