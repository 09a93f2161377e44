#include "dfc/continuum/nodal_average.hpp"

namespace dfc::continuum {

std::vector<double> nodal_average(std::span<const Triangle> triangles, Index node_count, std::span<const double> weights,
                                  std::span<const double> values) {
  std::vector<double> weighted_sum(node_count, 0.0);
  std::vector<double> weight_sum(node_count, 0.0);
  for (Index t = 0; t < triangles.size(); ++t) {
    for (const Index n : triangles[t]) {
      weighted_sum[n] += weights[t] * values[t];
      weight_sum[n] += weights[t];
    }
  }
  std::vector<double> averaged(triangles.size());
  for (Index t = 0; t < triangles.size(); ++t) {
    double sum = 0.0;
    for (const Index n : triangles[t]) sum += weighted_sum[n] / weight_sum[n];
    averaged[t] = sum / 3.0;
  }
  return averaged;
}

}  // namespace dfc::continuum
