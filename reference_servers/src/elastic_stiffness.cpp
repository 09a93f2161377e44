#include "dfc/reference/elastic_stiffness.hpp"

#include <algorithm>
#include <array>
#include <vector>

#include "dfc/fdm/hex_overlays.hpp"

namespace dfc::reference {

using fdm::Index;
using fdm::Vec3;

Eigen::SparseMatrix<double> assemble_elastic_stiffness(std::span<const fdm::Tetrahedron> tetrahedra, std::size_t gridpoint_count,
                                                       const constitutive::ElasticModuli& moduli) {
  const double shear = moduli.shear;
  const double bulk = moduli.bulk;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(tetrahedra.size() * (16 * 9) + tetrahedra.size() / fdm::kTetrahedraPerZone * (64 * 9));
  const auto add_block = [&](Index row_gp, Index col_gp, const Eigen::Matrix3d& block) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        entries.emplace_back(int(3 * row_gp) + i, int(3 * col_gp) + j, block(i, j));
  };

  for (std::size_t first = 0; first + fdm::kTetrahedraPerZone <= tetrahedra.size(); first += fdm::kTetrahedraPerZone) {
    // Volume-weighted divergence operator of the zone, per gridpoint: w = Σ_t V_t ∇N (§1.5).
    std::vector<std::pair<Index, Vec3>> divergence;
    double zone_volume = 0.0;  // Σ_t V_t over both overlays (= 2 V_zone)
    for (std::size_t t = first; t < first + fdm::kTetrahedraPerZone; ++t) {
      const fdm::Tetrahedron& tet = tetrahedra[t];
      zone_volume += tet.volume;
      std::array<Vec3, 4> gradient;
      for (std::size_t n = 0; n < 4; ++n) gradient[n] = -tet.area[n] / (3.0 * tet.volume);  // §1.3
      // Deviatoric part, per tetrahedron: K_mi,nj = ½ V [G (g_m·g_n) δ_ij + G g_mj g_ni − ⅔G g_mi g_nj].
      for (std::size_t m = 0; m < 4; ++m)
        for (std::size_t n = 0; n < 4; ++n) {
          const Eigen::Matrix3d block = shear * gradient[m].dot(gradient[n]) * Eigen::Matrix3d::Identity() +
                                        shear * gradient[n] * gradient[m].transpose() -
                                        (2.0 / 3.0) * shear * gradient[m] * gradient[n].transpose();
          add_block(tet.nodes[m], tet.nodes[n], fdm::kOverlayWeight * tet.volume * block);
        }
      for (std::size_t n = 0; n < 4; ++n) {
        const Vec3 weighted = tet.volume * gradient[n];
        auto it = std::find_if(divergence.begin(), divergence.end(), [&](const auto& e) { return e.first == tet.nodes[n]; });
        if (it == divergence.end()) {
          divergence.emplace_back(tet.nodes[n], weighted);
        } else {
          it->second += weighted;
        }
      }
    }
    // Volumetric part with the zone-averaged volumetric strain: ½ K_bulk w wᵀ / Σ_t V_t.
    for (const auto& [row_gp, w_row] : divergence)
      for (const auto& [col_gp, w_col] : divergence)
        add_block(row_gp, col_gp, (fdm::kOverlayWeight * bulk / zone_volume) * w_row * w_col.transpose());
  }

  const auto size = Eigen::Index(3 * gridpoint_count);
  Eigen::SparseMatrix<double> stiffness(size, size);
  stiffness.setFromTriplets(entries.begin(), entries.end());  // duplicates are summed
  return stiffness;
}

}  // namespace dfc::reference
