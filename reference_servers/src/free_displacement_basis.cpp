#include "dfc/reference/free_displacement_basis.hpp"

#include <vector>

#include <Eigen/Eigenvalues>

namespace dfc::reference {

using fdm::Index;
using fdm::Vec3;

Eigen::SparseMatrix<double> free_displacement_basis(const fdm::Solver& solver) {
  const std::size_t n_gp = solver.mesh().gridpoint_count();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(3 * n_gp);
  int column = 0;
  for (Index gp = 0; gp < n_gp; ++gp) {
    // The image of each unit vector under the constraint projection.
    Eigen::Matrix3d image;
    for (int c = 0; c < 3; ++c) image.col(c) = solver.constrained(gp, Vec3::Unit(c));
    if (image.isDiagonal(0.0)) {
      // Free or axis-aligned supports: keep the unit vectors exactly.
      for (int c = 0; c < 3; ++c)
        if (image(c, c) != 0.0) entries.emplace_back(int(3 * gp) + c, column++, 1.0);
      continue;
    }
    // A radial roller: the free directions are the range of the projection,
    // the eigenvectors of image·imageᵀ with eigenvalue 1 (the others are 0).
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(image * image.transpose());
    for (int k = 0; k < 3; ++k) {
      if (eigen.eigenvalues()[k] < 0.5) continue;
      for (int c = 0; c < 3; ++c)
        if (eigen.eigenvectors()(c, k) != 0.0) entries.emplace_back(int(3 * gp) + c, column, eigen.eigenvectors()(c, k));
      ++column;
    }
  }
  Eigen::SparseMatrix<double> basis(Eigen::Index(3 * n_gp), column);
  basis.setFromTriplets(entries.begin(), entries.end());
  return basis;
}

}  // namespace dfc::reference
