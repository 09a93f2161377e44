#include "dfc/continuum/pressure_projection.hpp"

#include <stdexcept>

#include <Eigen/SparseCore>

namespace dfc::continuum {

namespace {

using Eigen::VectorXd;

/// Element matrix of c M + τ S: c V/3 δ_ij (lumped mass) + τ V/36 (3 δ_ij − 1).
double element_entry(double volume, const ProjectionOperator& op, bool diagonal) {
  return diagonal ? op.mass_factor * volume / 3.0 + op.weight * volume / 18.0 : -op.weight * volume / 36.0;
}

bool is_fixed(const std::vector<bool>& fixed, Index node) { return !fixed.empty() && fixed[node]; }

/// y = (c M + τ S) x on the free nodes, y = x on the fixed ones, assembled
/// element by element (matrix-free: the geometry of the step).
VectorXd apply(std::span<const Triangle> triangles, std::span<const double> volumes, const ProjectionOperator& op,
               const std::vector<bool>& fixed, const VectorXd& x) {
  VectorXd y = VectorXd::Zero(x.size());
  for (Index t = 0; t < triangles.size(); ++t) {
    const Triangle& tri = triangles[t];
    double values[3];
    for (int i = 0; i < 3; ++i) values[i] = is_fixed(fixed, tri[i]) ? 0.0 : x(static_cast<Eigen::Index>(tri[i]));
    const double sum = values[0] + values[1] + values[2];
    const double v = volumes[t];
    for (int i = 0; i < 3; ++i)  // c (V/3) x_i + τ (V/36)(3 x_i − Σ x)
      y(static_cast<Eigen::Index>(tri[i])) += op.mass_factor * v / 3.0 * values[i] + op.weight * v / 36.0 * (3.0 * values[i] - sum);
  }
  for (Index n = 0; n < fixed.size(); ++n)
    if (fixed[n]) y(static_cast<Eigen::Index>(n)) = x(static_cast<Eigen::Index>(n));
  return y;
}

// Conjugate-gradient stopping test: the residual relative to the right-hand
// side. 1e-11 is about the round-off of applying a matrix whose entries span
// τ = K/G ~ 10⁴ (ν = 0.4999) times the mass term.
constexpr double kRelativeTolerance = 1e-11;
// More iterations than this mean the preconditioner's geometry is stale: renew it.
constexpr int kIterationsBeforeRenewal = 4;
constexpr int kMaximumIterations = 50;

}  // namespace

void PressureProjection::factorise(std::span<const Triangle> triangles, Index node_count, std::span<const double> volumes,
                                   const ProjectionOperator& op, const std::vector<bool>& fixed) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(9 * triangles.size() + fixed.size());
  for (Index t = 0; t < triangles.size(); ++t)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (!is_fixed(fixed, triangles[t][i]) && !is_fixed(fixed, triangles[t][j]))
          entries.emplace_back(static_cast<int>(triangles[t][i]), static_cast<int>(triangles[t][j]),
                               element_entry(volumes[t], op, i == j));
  for (Index n = 0; n < fixed.size(); ++n)
    if (fixed[n]) entries.emplace_back(static_cast<int>(n), static_cast<int>(n), 1.0);
  Eigen::SparseMatrix<double> matrix(static_cast<Eigen::Index>(node_count), static_cast<Eigen::Index>(node_count));
  matrix.setFromTriplets(entries.begin(), entries.end());
  factorisation_.compute(matrix);
  if (factorisation_.info() != Eigen::Success) throw std::runtime_error("pressure projection: the matrix M + tau S is not positive definite");
  factorised_ = true;
  factorised_triangles_.assign(triangles.begin(), triangles.end());
  factorised_nodes_ = node_count;
  factorised_operator_ = op;
  factorised_fixed_ = fixed;
}

std::vector<double> PressureProjection::nodal_solution(std::span<const Triangle> triangles, Index node_count,
                                                       std::span<const double> volumes, double weight,
                                                       std::span<const double> values) {
  std::vector<double> rhs(node_count, 0.0);
  for (Index t = 0; t < triangles.size(); ++t)
    for (const Index n : triangles[t]) rhs[n] += volumes[t] * values[t] / 3.0;
  return solve(triangles, volumes, {1.0, weight}, {}, rhs);
}

std::vector<double> PressureProjection::solve(std::span<const Triangle> triangles, std::span<const double> volumes,
                                              const ProjectionOperator& op, const std::vector<bool>& fixed,
                                              std::span<const double> nodal_rhs) {
  const Index node_count = nodal_rhs.size();
  VectorXd rhs(static_cast<Eigen::Index>(node_count));
  for (Index n = 0; n < node_count; ++n) rhs(static_cast<Eigen::Index>(n)) = is_fixed(fixed, n) ? 0.0 : nodal_rhs[n];
  last_iterations_ = 0;
  const double rhs_norm = rhs.norm();
  if (rhs_norm == 0.0) return std::vector<double>(node_count, 0.0);
  const bool same_mesh = factorised_ && factorised_nodes_ == node_count && factorised_operator_.mass_factor == op.mass_factor &&
                         factorised_operator_.weight == op.weight && factorised_fixed_ == fixed &&
                         std::equal(triangles.begin(), triangles.end(), factorised_triangles_.begin(), factorised_triangles_.end());
  if (!same_mesh) factorise(triangles, node_count, volumes, op, fixed);

  // Preconditioned conjugate gradients from the preconditioner's own
  // solution, which is usually converged already (one triangular solve and
  // one product).
  VectorXd x = factorisation_.solve(rhs);
  VectorXd r = rhs - apply(triangles, volumes, op, fixed, x);
  int iterations = 0;
  if (r.norm() > kRelativeTolerance * rhs_norm) {
    VectorXd z = factorisation_.solve(r);
    VectorXd p = z;
    double rz = r.dot(z);
    while (r.norm() > kRelativeTolerance * rhs_norm && iterations < kMaximumIterations) {
      const VectorXd ap = apply(triangles, volumes, op, fixed, p);
      const double step = rz / p.dot(ap);
      x += step * p;
      r -= step * ap;
      z = factorisation_.solve(r);
      const double rz_next = r.dot(z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
      ++iterations;
    }
  }
  last_iterations_ = iterations;
  if (r.norm() > kRelativeTolerance * rhs_norm) {
    // Not converged with the stale preconditioner: solve with a fresh factorisation.
    factorise(triangles, node_count, volumes, op, fixed);
    x = factorisation_.solve(rhs);
  } else if (iterations > kIterationsBeforeRenewal) {
    factorise(triangles, node_count, volumes, op, fixed);
  }
  return {x.data(), x.data() + x.size()};
}

}  // namespace dfc::continuum
