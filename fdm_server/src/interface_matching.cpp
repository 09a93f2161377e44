#include "dfc/fdm/interface_matching.hpp"

#include <algorithm>
#include <sstream>

#include "dfc/common/errors.hpp"

namespace dfc::fdm {

std::vector<Index> match_nodes_to_gridpoints(const Mesh& mesh, std::span<const Index> candidates, std::span<const std::int64_t> node_ids,
                                             std::span<const double> coordinates, double tolerance) {
  constexpr std::size_t kListed = 10;
  // Candidates sorted by x: each node then scans only the x-window [x − tol, x + tol].
  std::vector<Index> by_x(candidates.begin(), candidates.end());
  std::sort(by_x.begin(), by_x.end(), [&](Index a, Index b) { return mesh.points[a].x() < mesh.points[b].x(); });

  std::vector<Index> matched(node_ids.size());
  std::vector<std::size_t> unmatched;
  for (std::size_t r = 0; r < node_ids.size(); ++r) {
    const Vec3 x(coordinates[3 * r], coordinates[3 * r + 1], coordinates[3 * r + 2]);
    auto it = std::lower_bound(by_x.begin(), by_x.end(), x.x() - tolerance, [&](Index gp, double value) { return mesh.points[gp].x() < value; });
    bool found = false;
    for (; it != by_x.end() && mesh.points[*it].x() <= x.x() + tolerance; ++it)
      if ((mesh.points[*it] - x).cwiseAbs().maxCoeff() <= tolerance) {
        matched[r] = *it;
        found = true;
        break;
      }
    if (!found) unmatched.push_back(r);
  }

  std::ostringstream message;
  if (!unmatched.empty()) {
    message << unmatched.size() << " of " << node_ids.size() << " interface nodes are not on the coupling face group (tolerance "
            << tolerance << " m):";
    for (std::size_t i = 0; i < std::min(kListed, unmatched.size()); ++i) {
      const std::size_t r = unmatched[i];
      message << " id " << node_ids[r] << " at (" << coordinates[3 * r] << ", " << coordinates[3 * r + 1] << ", " << coordinates[3 * r + 2] << ")"
              << (i + 1 < std::min(kListed, unmatched.size()) ? ";" : "");
    }
    if (unmatched.size() > kListed) message << " and " << unmatched.size() - kListed << " more";
    message << "; both sides must use the same interface geometry";
    throw UserError(message.str());
  }
  std::vector<Index> sorted = matched;
  std::sort(sorted.begin(), sorted.end());
  if (const auto dup = std::adjacent_find(sorted.begin(), sorted.end()); dup != sorted.end()) {
    message << "two interface nodes lie on the same gridpoint " << *dup << "; interface nodes must be distinct";
    throw UserError(message.str());
  }
  return matched;
}

}  // namespace dfc::fdm
