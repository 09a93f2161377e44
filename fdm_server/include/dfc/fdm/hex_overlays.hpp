#pragma once
// Hexahedral zone → two overlays of five tetrahedra (docs/theory/fdm.md §1.2).
#include <array>

#include "dfc/fdm/mesh.hpp"
#include "dfc/fdm/tetrahedron.hpp"

namespace dfc::fdm {

inline constexpr Index kTetrahedraPerZone = 10;
/// Each overlay represents the whole zone, so every tetrahedron's force, mass and
/// body-force contribution is halved (§1.7, §1.10 dynamic).
inline constexpr double kOverlayWeight = 0.5;

/// Local corner indices (FLAC3D order) of the 10 tetrahedra: overlay A (central
/// first) then overlay B. This is the §1.2 table with two vertices swapped where
/// needed so that every tetrahedron of a right-handed zone has positive volume.
inline constexpr std::array<std::array<int, 4>, kTetrahedraPerZone> kOverlayTetrahedra = {{
    {0, 4, 5, 6}, {2, 0, 4, 5}, {3, 0, 5, 6}, {1, 0, 6, 4}, {7, 6, 5, 4},  // overlay A
    {1, 2, 3, 7}, {5, 2, 7, 3}, {0, 1, 2, 3}, {4, 1, 7, 2}, {6, 1, 3, 7},  // overlay B
}};

/// The 10 tetrahedra of `zone`, in kOverlayTetrahedra order, volumes signed.
[[nodiscard]] std::array<Tetrahedron, kTetrahedraPerZone> zone_tetrahedra(const Mesh& mesh, Index zone);

}  // namespace dfc::fdm
