#pragma once
// The flat interface of the protocol test servers (fixture_backend.cpp, and
// fuzz/fuzz_backend.cpp): side × side nodes on the unit grid in z = 0, ids
// from 1000, two triangles per cell counter-clockwise seen from +z, so the
// facet normals point up, out of the body below (SPEC.md §4.3).
#include <cstdint>

#include "dfc/protocol/solver_backend.hpp"

namespace dfc::protocol::testing {

inline InterfaceMesh square_grid_mesh(std::int64_t side) {
  InterfaceMesh mesh;
  for (std::int64_t j = 0; j < side; ++j)
    for (std::int64_t i = 0; i < side; ++i) {
      mesh.node_ids.push_back(1000 + j * side + i);
      mesh.coordinates.insert(mesh.coordinates.end(), {double(i), double(j), 0.0});
    }
  for (std::int64_t j = 0; j + 1 < side; ++j)
    for (std::int64_t i = 0; i + 1 < side; ++i) {
      const std::int64_t a = j * side + i;
      mesh.facets.insert(mesh.facets.end(), {a, a + 1, a + side + 1, a, a + side + 1, a + side});
    }
  return mesh;
}

}  // namespace dfc::protocol::testing
