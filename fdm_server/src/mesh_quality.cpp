#include "dfc/fdm/mesh_quality.hpp"

#include <algorithm>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "dfc/common/errors.hpp"
#include "dfc/fdm/hex_overlays.hpp"

namespace dfc::fdm {

namespace {

// The 12 edges of a hexahedron: corner pairs (FLAC3D order) that differ in one
// local coordinate.
constexpr std::array<std::array<int, 2>, 12> kHexEdges = {{
    {0, 1}, {2, 4}, {3, 6}, {5, 7},  // along i
    {0, 2}, {1, 4}, {3, 5}, {6, 7},  // along j
    {0, 3}, {1, 6}, {2, 5}, {4, 7},  // along k
}};

// "zones 3 (x, y, z), 17 (…) and 5 more": the offending zones, named so that
// the user can find them.
std::string list_zones(const Mesh& mesh, const std::vector<Index>& zones) {
  constexpr std::size_t kListed = 10;
  std::ostringstream out;
  out.precision(4);
  for (std::size_t i = 0; i < std::min(kListed, zones.size()); ++i) {
    const Vec3 c = mesh.zone_centroid(zones[i]);
    out << (i ? ", " : "") << zones[i] << " (centroid " << c.x() << ", " << c.y() << ", " << c.z() << " m)";
  }
  if (zones.size() > kListed) out << " and " << zones.size() - kListed << " more";
  return out.str();
}

}  // namespace

double zone_aspect_ratio(const Mesh& mesh, Index zone) {
  const HexZone& corners = mesh.zones[zone];
  double longest = 0.0;
  double shortest = std::numeric_limits<double>::infinity();
  for (const auto& [a, b] : kHexEdges) {
    const double length = (mesh.points[corners[std::size_t(a)]] - mesh.points[corners[std::size_t(b)]]).norm();
    longest = std::max(longest, length);
    shortest = std::min(shortest, length);
  }
  return longest / shortest;
}

void check_aspect_ratios(const Mesh& mesh, double limit, std::string_view what) {
  std::vector<Index> bad;
  double worst = 0.0;
  for (Index zone = 0; zone < mesh.zone_count(); ++zone) {
    const double ratio = zone_aspect_ratio(mesh, zone);
    worst = std::max(worst, ratio);
    if (!(ratio <= limit)) bad.push_back(zone);
  }
  if (bad.empty()) return;
  std::ostringstream message;
  message.precision(3);
  message << what << ": " << bad.size() << " zone(s) have an aspect ratio (longest/shortest edge) above " << limit << " (worst "
          << worst << "): zones " << list_zones(mesh, bad) << "; refine or regrade the mesh, or raise max_aspect_ratio";
  throw UserError(message.str());
}

void check_mesh_quality(const Mesh& mesh) {
  std::vector<Index> bad_zones;
  for (Index zone = 0; zone < mesh.zone_count(); ++zone) {
    const auto tets = zone_tetrahedra(mesh, zone);
    if (std::any_of(tets.begin(), tets.end(), [](const Tetrahedron& t) { return !(t.volume > 0.0); })) bad_zones.push_back(zone);
  }
  if (bad_zones.empty()) return;
  throw UserError("the mesh has " + std::to_string(bad_zones.size()) +
                  " zone(s) with a non-positive tetrahedron volume (inverted or badly distorted hexahedra, or corners "
                  "not in FLAC3D order): zones " + list_zones(mesh, bad_zones) + "; fix the mesh geometry or grading");
}

}  // namespace dfc::fdm
