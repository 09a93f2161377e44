#include "dfc/continuum/equilibrium_correction.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

namespace dfc::continuum {

namespace {

// The four stress components of an axisymmetric triangle and their weights
// in |σ|² = σ:σ (the shear rz appears twice).
constexpr int kComponents = 4;  // rr, θθ, zz, rz
constexpr std::array<double, kComponents> kNormWeights{1.0, 1.0, 1.0, 2.0};
// A Aᵀ is singular: a constant stress exerts no net axial force on its
// triangle, so the z rows of a group of adjustable triangles whose nodes are
// all free sum to zero. The forces to make up have no component along that
// sum either (the same holds for the old triangles that covered the group),
// so 1e-12 of the largest diagonal entry, far below the other eigenvalues,
// only makes the factorisation definite.
constexpr double kRegularisation = 1e-12;

}  // namespace

NodalForceCorrection::NodalForceCorrection(std::span<const Point> nodes, std::span<const Triangle> triangles,
                                           const std::vector<bool>& adjustable, std::span<const std::array<bool, 2>> prescribed) {
  std::map<std::array<Index, 2>, int> row_of;
  for (Index t = 0; t < triangles.size(); ++t) {
    if (!adjustable[t]) continue;
    adjusted_.push_back(t);
    for (const Index n : triangles[t])
      for (Index a = 0; a < 2; ++a)
        if (!prescribed[n][a] && row_of.try_emplace({n, a}, static_cast<int>(rows_.size())).second) rows_.push_back({n, a});
  }
  // Columns: the scaled unknowns y = √(w V) Δσ, so that the minimum-norm y
  // is the minimum Σ w V Δσ² correction.
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t k = 0; k < adjusted_.size(); ++k) {
    const Triangle& tri = triangles[adjusted_[k]];
    const TriangleGeometry g = triangle_geometry(gather(nodes, tri));
    const double volume = g.volume();
    std::array<double, kComponents> scale{};
    for (std::size_t c = 0; c < kComponents; ++c) scale[c] = 1.0 / std::sqrt(kNormWeights[c] * volume);
    scales_.push_back(scale);
    const int column = kComponents * static_cast<int>(k);
    for (std::size_t i = 0; i < 3; ++i) {
      // internal_forces(): f_r = V (σ_rr ∂N/∂r + σ_rz ∂N/∂z + σ_θθ/(3 r̄)), f_z = V (σ_rz ∂N/∂r + σ_zz ∂N/∂z).
      if (const auto r = row_of.find({tri[i], 0}); r != row_of.end()) {
        entries.emplace_back(r->second, column + 0, volume * g.dn_dr[i] * scale[0]);
        entries.emplace_back(r->second, column + 1, volume / (3.0 * g.centroid_r) * scale[1]);
        entries.emplace_back(r->second, column + 3, volume * g.dn_dz[i] * scale[3]);
      }
      if (const auto z = row_of.find({tri[i], 1}); z != row_of.end()) {
        entries.emplace_back(z->second, column + 2, volume * g.dn_dz[i] * scale[2]);
        entries.emplace_back(z->second, column + 3, volume * g.dn_dr[i] * scale[3]);
      }
    }
  }
  matrix_.resize(static_cast<Eigen::Index>(rows_.size()), static_cast<Eigen::Index>(kComponents * adjusted_.size()));
  matrix_.setFromTriplets(entries.begin(), entries.end());
  if (rows_.empty()) return;
  Eigen::SparseMatrix<double> normal = matrix_ * matrix_.transpose();
  const double largest = normal.diagonal().maxCoeff();
  for (Eigen::Index i = 0; i < normal.rows(); ++i) normal.coeffRef(i, i) += kRegularisation * largest;
  normal_.compute(normal);
  if (normal_.info() != Eigen::Success) throw std::runtime_error("remesh: the equilibrium correction's matrix could not be factorised");
}

double NodalForceCorrection::apply(std::span<const Point> force_change, std::span<Stress> stresses) const {
  Eigen::VectorXd target(static_cast<Eigen::Index>(rows_.size()));
  for (std::size_t row = 0; row < rows_.size(); ++row)
    target(static_cast<Eigen::Index>(row)) = force_change[rows_[row][0]][static_cast<Eigen::Index>(rows_[row][1])];
  const double residual = target.norm();
  if (residual == 0.0) return 0.0;
  // The minimum-norm solution of A y = b: y = Aᵀ (A Aᵀ)⁻¹ b.
  const Eigen::VectorXd y = matrix_.transpose() * normal_.solve(target);
  for (std::size_t k = 0; k < adjusted_.size(); ++k) {
    Stress& s = stresses[adjusted_[k]];
    const auto change = [&](int c) {
      return y(kComponents * static_cast<Eigen::Index>(k) + c) * scales_[k][static_cast<std::size_t>(c)];
    };
    s.xx += change(0);
    s.yy += change(1);
    s.zz += change(2);
    s.zx += change(3);
  }
  return residual;
}

}  // namespace dfc::continuum
