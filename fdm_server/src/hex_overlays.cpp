#include "dfc/fdm/hex_overlays.hpp"

namespace dfc::fdm {

std::array<Tetrahedron, kTetrahedraPerZone> zone_tetrahedra(const Mesh& mesh, Index zone) {
  const HexZone& corners = mesh.zones[zone];
  std::array<Tetrahedron, kTetrahedraPerZone> tets;
  for (std::size_t t = 0; t < kTetrahedraPerZone; ++t) {
    std::array<Index, 4> nodes{};
    std::array<Vec3, 4> x;
    for (std::size_t n = 0; n < 4; ++n) {
      nodes[n] = corners[std::size_t(kOverlayTetrahedra[t][n])];
      x[n] = mesh.points[nodes[n]];
    }
    tets[t] = make_tetrahedron(nodes, x);
  }
  return tets;
}

}  // namespace dfc::fdm
