#include "dfc/continuum/nodal_average.hpp"

namespace dfc::continuum {

std::vector<double> nodal_means(std::span<const Triangle> triangles, Index node_count, std::span<const double> weights,
                                std::span<const double> values) {
  std::vector<double> weighted_sum(node_count, 0.0);
  std::vector<double> weight_sum(node_count, 0.0);
  for (Index t = 0; t < triangles.size(); ++t) {
    for (const Index n : triangles[t]) {
      weighted_sum[n] += weights[t] * values[t];
      weight_sum[n] += weights[t];
    }
  }
  for (Index n = 0; n < node_count; ++n)
    if (weight_sum[n] > 0.0) weighted_sum[n] /= weight_sum[n];
  return weighted_sum;
}

std::vector<double> triangle_means(std::span<const Triangle> triangles, std::span<const double> nodal_values) {
  std::vector<double> means(triangles.size());
  for (Index t = 0; t < triangles.size(); ++t) {
    double sum = 0.0;
    for (const Index n : triangles[t]) sum += nodal_values[n];
    means[t] = sum / 3.0;
  }
  return means;
}

std::vector<double> nodal_average(std::span<const Triangle> triangles, Index node_count, std::span<const double> weights,
                                  std::span<const double> values) {
  return triangle_means(triangles, nodal_means(triangles, node_count, weights, values));
}

}  // namespace dfc::continuum
