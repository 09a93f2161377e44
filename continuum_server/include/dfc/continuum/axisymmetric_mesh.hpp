#pragma once
// A mesh of linear triangles in the axisymmetric (r, z) half-plane
// (docs/continuum_pile.md §3): node coordinates, triangles listed counter-
// clockwise, and named groups of nodes and of boundary edges for boundary
// conditions. Edges of a group are oriented with the body on their left, so
// their outward normal is the edge direction turned clockwise.
#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace dfc::continuum {

/// A point of the r–z half-plane: (r, z), m.
using Point = Eigen::Vector2d;
using Index = std::size_t;
using Triangle = std::array<Index, 3>;
/// A boundary edge from its first node to its second, the body on its left.
using Edge = std::array<Index, 2>;

struct AxisymmetricMesh {
  std::vector<Point> nodes;
  std::vector<Triangle> triangles;
  std::map<std::string, std::vector<Index>> node_groups;
  std::map<std::string, std::vector<Edge>> edge_groups;

  /// The named node group; a programmer error (assertion) if absent.
  [[nodiscard]] const std::vector<Index>& node_group(const std::string& name) const;
  [[nodiscard]] const std::vector<Edge>& edge_group(const std::string& name) const;
};

}  // namespace dfc::continuum
