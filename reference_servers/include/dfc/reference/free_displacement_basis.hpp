#pragma once
// The supports of the FDM's boundary conditions as a change of unknowns for a
// static solve: u = T q, where the columns of T span, at each gridpoint, the
// directions that its fixed and roller conditions leave free
// (fdm::Solver::constrained, docs/theory/fdm.md §1.8). The constrained system is
// Tᵀ K T q = Tᵀ f: reactions drop out, exactly as the explicit solver drops the
// held components of the out-of-balance force.
#include <Eigen/SparseCore>

#include "dfc/fdm/solver.hpp"

namespace dfc::reference {

/// T (3N × m, orthonormal columns, grouped by gridpoint in ascending order).
/// A free gridpoint contributes the three unit vectors, a plane roller the two
/// in-plane unit vectors, a radial roller the tangential and (unless held) the
/// vertical direction.
[[nodiscard]] Eigen::SparseMatrix<double> free_displacement_basis(const fdm::Solver& solver);

}  // namespace dfc::reference
