#include "dfc/continuum/boundary_edges.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace dfc::continuum {

std::vector<Edge> boundary_edges(std::span<const Triangle> triangles) {
  // Undirected edge → (number of triangles, the orientation of the last one).
  std::map<std::pair<Index, Index>, std::pair<int, Edge>> uses;
  for (const Triangle& t : triangles) {
    for (int i = 0; i < 3; ++i) {
      const Edge directed{t[i], t[(i + 1) % 3]};
      auto& entry = uses[{std::min(directed[0], directed[1]), std::max(directed[0], directed[1])}];
      ++entry.first;
      entry.second = directed;
    }
  }
  std::vector<Edge> boundary;
  for (const auto& [key, entry] : uses)
    if (entry.first == 1) boundary.push_back(entry.second);
  return boundary;
}

}  // namespace dfc::continuum
