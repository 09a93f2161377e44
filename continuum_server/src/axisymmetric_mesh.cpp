#include "dfc/continuum/axisymmetric_mesh.hpp"

#include <cassert>

namespace dfc::continuum {

const std::vector<Index>& AxisymmetricMesh::node_group(const std::string& name) const {
  const auto it = node_groups.find(name);
  assert(it != node_groups.end() && "unknown node group");
  return it->second;
}

const std::vector<Edge>& AxisymmetricMesh::edge_group(const std::string& name) const {
  const auto it = edge_groups.find(name);
  assert(it != edge_groups.end() && "unknown edge group");
  return it->second;
}

}  // namespace dfc::continuum
