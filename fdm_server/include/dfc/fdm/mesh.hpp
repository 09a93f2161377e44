#pragma once
// Mesh: gridpoints, 8-node hexahedral zones and named boundary face groups.
//
// Zone corners are in FLAC3D B8 order (docs/theory/fdm.md §1.2): with local corner
// coordinates (i,j,k) ∈ {0,1}³, gp0=(000) gp1=(100) gp2=(010) gp3=(001)
// gp4=(110) gp5=(011) gp6=(101) gp7=(111). A face is 4 gridpoints ordered so
// that the right-hand normal points OUT of the body.
#include <array>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "dfc/fdm/types.hpp"

namespace dfc::fdm {

using HexZone = std::array<Index, 8>;   ///< gridpoint indices, FLAC3D order
using FaceQuad = std::array<Index, 4>;  ///< gridpoint indices, right-hand normal outward

/// Local (i,j,k) corner coordinates of the FLAC3D B8 order.
inline constexpr std::array<std::array<int, 3>, 8> kFlacCornerOffsets = {
    {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}, {1, 1, 1}}};

/// VTK_HEXAHEDRON corner k is FLAC3D corner kVtkFromFlac[k]
/// (VTK order 000,100,110,010,001,101,111,011; meshio flac3d mapping, §1.2).
inline constexpr std::array<int, 8> kVtkFromFlac = {0, 1, 4, 2, 3, 6, 7, 5};

struct Mesh {
  std::vector<Vec3> points;
  std::vector<HexZone> zones;
  std::map<std::string, std::vector<FaceQuad>, std::less<>> face_groups;

  [[nodiscard]] std::size_t gridpoint_count() const noexcept { return points.size(); }
  [[nodiscard]] std::size_t zone_count() const noexcept { return zones.size(); }
  /// The faces of `name`; throws dfc::UserError naming the known groups.
  [[nodiscard]] const std::vector<FaceQuad>& face_group(std::string_view name) const;
  [[nodiscard]] bool has_face_group(std::string_view name) const { return face_groups.find(name) != face_groups.end(); }
  /// Comma-separated group names, for error messages.
  [[nodiscard]] std::string face_group_names() const;
  /// Gridpoints of a face group, ascending and unique.
  [[nodiscard]] std::vector<Index> face_group_gridpoints(std::string_view name) const;
  [[nodiscard]] Vec3 zone_centroid(Index zone) const;
  [[nodiscard]] Vec3 face_centroid(const FaceQuad& face) const;
  /// Length of the bounding-box diagonal (the "model size" used for tolerances).
  [[nodiscard]] double size() const;
  [[nodiscard]] double min_z() const;
  [[nodiscard]] double max_z() const;
};

/// Vector area of a (possibly non-planar) quad: ½ d₁₃ × d₂₄. Exact for bilinear
/// faces; points along the right-hand normal of the corner order.
[[nodiscard]] Vec3 quad_area_vector(const Mesh& mesh, const FaceQuad& face);

/// Throws dfc::UserError naming the zones that have a tetrahedron (of either
/// overlay, §1.2) with non-positive volume: inverted or badly distorted zones.
void check_mesh_quality(const Mesh& mesh);

}  // namespace dfc::fdm
