#pragma once
// Zone quality checks beyond the inverted-zone check every solver runs
// (check_mesh_quality in mesh.hpp): elongated zones make the constant-strain
// tetrahedra stiff and inaccurate in the elongated direction, so meshes meant
// for the pile problem are checked for their aspect ratio.
#include <string_view>

#include "dfc/fdm/mesh.hpp"

namespace dfc::fdm {

/// Longest / shortest of the 12 edges of hexahedral zone `zone`.
[[nodiscard]] double zone_aspect_ratio(const Mesh& mesh, Index zone);

/// Throws dfc::UserError naming the zones (with their centroids) whose aspect
/// ratio exceeds `limit`, and the worst value. `what` names the mesh in the message.
void check_aspect_ratios(const Mesh& mesh, double limit, std::string_view what);

}  // namespace dfc::fdm
