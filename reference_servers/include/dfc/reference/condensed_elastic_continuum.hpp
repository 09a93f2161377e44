#pragma once
// CondensedElasticContinuum: the fdm_server model solved statically and
// condensed to the coupling interface (docs/theory/coupling.md §1, "implicit linear
// elasticity condensed to the interface").
//
// Equilibrium of the explicit solver's gridpoint forces (docs/theory/fdm.md §1.7,
// §1.8) with an isotropic elastic model and the stress σ = σ₀ + D ε̄(u) is
//   f_int(σ₀) + ρgV/4 + face loads − K u + f_interface = 0,
// i.e. K u = r₀ + f_interface with r₀ the force the continuum exerts on each
// gridpoint in its initial state (fdm::Solver::force_exerted_on_gridpoint at
// u = 0). With a geostatic initial stress r₀ is zero inside the body (§2(c))
// and equals minus the in-situ traction on the unsupported interface; so u is
// the displacement INCREMENT relative to the geostatic state, and interface
// forces equal to the in-situ traction leave the interface where it is.
//
// With the supports as u = T q (free_displacement_basis) and E the selection of
// the interface components, the interface displacement is
//   u_I = C f_I + u_I⁰,   C = Eᵀ T (Tᵀ K T)⁻¹ Tᵀ E,   u_I⁰ = Eᵀ T (Tᵀ K T)⁻¹ Tᵀ r₀:
// C is the interface compliance (Schur complement of the interior), computed
// once with a sparse LDLᵀ factorization; each load then costs one dense mat-vec.
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

#include "dfc/fdm/solver.hpp"

namespace dfc::reference {

class CondensedElasticContinuum {
 public:
  /// Assembles K for the solver's mesh and elastic moduli, applies its
  /// supports, factorizes and condenses to `interface_gridpoints` (the rows of
  /// the interface arrays). Throws dfc::UserError when the supports leave a
  /// rigid-body motion free (singular stiffness).
  CondensedElasticContinuum(const fdm::Solver& solver, std::vector<fdm::Index> interface_gridpoints);

  /// u_I = C f_I + u_I⁰ for interface forces f_I (f64 [n,3] row-major, N); m.
  [[nodiscard]] Eigen::VectorXd interface_displacement(std::span<const double> interface_force) const;
  /// The whole displacement field for interface forces f_I (one back
  /// substitution with the stored factorization); m per gridpoint.
  [[nodiscard]] std::vector<fdm::Vec3> displacement_field(std::span<const double> interface_force) const;

  /// C, 3n × 3n, m/N: component 3r+c of the displacement per unit force on component 3s+d.
  [[nodiscard]] const Eigen::MatrixXd& compliance() const { return compliance_; }
  /// u_I⁰, 3n, m: where the interface goes with no interface force.
  [[nodiscard]] const Eigen::VectorXd& in_situ_displacement() const { return in_situ_displacement_; }
  [[nodiscard]] const std::vector<fdm::Index>& interface_gridpoints() const { return interface_gridpoints_; }

 private:
  [[nodiscard]] Eigen::VectorXd reduced_load(std::span<const double> interface_force) const;

  std::vector<fdm::Index> interface_gridpoints_;
  Eigen::SparseMatrix<double> basis_;            // T: 3N × m
  Eigen::SparseMatrix<double> interface_basis_;  // Tᵀ E: m × 3n
  Eigen::VectorXd reduced_initial_force_;        // Tᵀ r₀
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factorization_;  // of Tᵀ K T
  Eigen::MatrixXd compliance_;
  Eigen::VectorXd in_situ_displacement_;
};

}  // namespace dfc::reference
