#include "dfc/continuum/darcy_flow.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dfc/continuum/triangle_kinematics.hpp"

namespace dfc::continuum {

std::vector<double> darcy_outflow(std::span<const Point> nodes, std::span<const Triangle> triangles, double mobility,
                                  std::span<const double> pore_pressures) {
  std::vector<double> outflow(nodes.size(), 0.0);
  for (const Triangle& tri : triangles) {
    const TriangleGeometry g = triangle_geometry(gather(nodes, tri));
    double gradient_r = 0.0, gradient_z = 0.0;
    for (int i = 0; i < 3; ++i) {
      gradient_r += g.dn_dr[i] * pore_pressures[tri[i]];
      gradient_z += g.dn_dz[i] * pore_pressures[tri[i]];
    }
    const double conductance = g.volume() * mobility;
    for (int i = 0; i < 3; ++i) outflow[tri[i]] += conductance * (g.dn_dr[i] * gradient_r + g.dn_dz[i] * gradient_z);
  }
  return outflow;
}

std::vector<double> darcy_row_sums(std::span<const Point> nodes, std::span<const Triangle> triangles, double mobility) {
  std::vector<double> sums(nodes.size(), 0.0);
  for (const Triangle& tri : triangles) {
    const TriangleGeometry g = triangle_geometry(gather(nodes, tri));
    const double conductance = g.volume() * mobility;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) sums[tri[i]] += conductance * std::abs(g.dn_dr[i] * g.dn_dr[j] + g.dn_dz[i] * g.dn_dz[j]);
  }
  return sums;
}

double stable_flow_step(std::span<const double> storage, std::span<const double> row_sums, const std::vector<bool>& free_nodes) {
  // Forward Euler on C ṗ = −H p is stable for Δt ≤ 2/λ_max(C⁻¹H), and
  // λ_max ≤ max_i Σ_j |H_ij| / C_i (Gershgorin).
  double step = std::numeric_limits<double>::infinity();
  for (std::size_t n = 0; n < storage.size(); ++n)
    if (free_nodes[n] && row_sums[n] > 0.0) step = std::min(step, 2.0 * storage[n] / row_sums[n]);
  return step;
}

}  // namespace dfc::continuum
