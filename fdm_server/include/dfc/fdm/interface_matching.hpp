#pragma once
// Matching a partner's interface nodes to this mesh's gridpoints by position.
#include <cstdint>
#include <span>
#include <vector>

#include "dfc/fdm/mesh.hpp"

namespace dfc::fdm {

/// For each node (coordinates: 3 per node), the gridpoint among `candidates`
/// within `tolerance` in every coordinate. Throws dfc::UserError listing the
/// unmatched nodes (by id and position) or nodes that match the same gridpoint.
[[nodiscard]] std::vector<Index> match_nodes_to_gridpoints(const Mesh& mesh, std::span<const Index> candidates,
                                                           std::span<const std::int64_t> node_ids, std::span<const double> coordinates,
                                                           double tolerance);

}  // namespace dfc::fdm
