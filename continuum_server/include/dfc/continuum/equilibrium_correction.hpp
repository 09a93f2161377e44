#pragma once
// The stress correction that makes a transferred stress field exert given
// nodal forces (docs/continuum_pile.md §5): after a remesh the stresses of
// a set of triangles are changed by the smallest volume-weighted amount
// Σ_t V_t |Δσ_t|² for which their internal nodal forces ∫ Bᵀσ dV change by
// given amounts at every free (not prescribed) component of their nodes. A
// body in equilibrium before the remesh is then in equilibrium after it,
// node by node, whatever the transfer's error: the equality part of the
// equilibrium-preserving transfer of Brancherie, Villon & Ibrahimbegović
// (2008); the plastic admissibility is the model's (axisymmetric_solver_remesh.cpp
// alternates the two).
#include <array>
#include <span>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "dfc/continuum/axisymmetric_mesh.hpp"
#include "dfc/continuum/triangle_kinematics.hpp"

namespace dfc::continuum {

class NodalForceCorrection {
 public:
  /// The operator of the triangles with `adjustable[t]` on the current
  /// geometry; the rows are the components of their nodes that are not
  /// `prescribed` (a support's reaction is whatever the stresses give).
  NodalForceCorrection(std::span<const Point> nodes, std::span<const Triangle> triangles, const std::vector<bool>& adjustable,
                       std::span<const std::array<bool, 2>> prescribed);

  /// Adds to the adjustable triangles' stresses (rr, θθ, zz, rz) the
  /// minimum-norm correction (weight V_t, the shear counted twice as in
  /// |σ|²) whose nodal forces are `force_change` at every row. Returns
  /// ‖force_change‖ over the rows, N.
  double apply(std::span<const Point> force_change, std::span<Stress> stresses) const;

 private:
  std::vector<std::array<Index, 2>> rows_;  ///< (node, axis) of each row
  std::vector<Index> adjusted_;             ///< the triangle of each group of four columns
  Eigen::SparseMatrix<double> matrix_;      ///< A: scaled unknowns → nodal forces
  /// A Aᵀ (+ a regularisation of its null space, see the .cpp), factorised once.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> normal_;
  std::vector<std::array<double, 4>> scales_;  ///< Δσ = scale × y per column
};

}  // namespace dfc::continuum
