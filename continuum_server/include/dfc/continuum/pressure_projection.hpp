#pragma once
// The polynomial pressure projection of Dohrmann & Bochev (2004) for linear
// triangles with a linear (nodal) pressure (docs/continuum_pile.md §3).
//
// Equal-order P1–P1 displacement–pressure triangles violate the inf–sup
// condition; Dohrmann & Bochev (2004, Int. J. Numer. Meth. Fluids 46:183–201,
// doi:10.1002/fld.752) stabilise them by penalising the difference between
// the pressure and its L² projection Π onto piecewise constants (their
// stabilised form, written here for a nearly incompressible solid as in
// Bochev, Dohrmann & Gunzburger 2006, doi:10.1137/050631227):
//   ∫ q ε_v dV − (1/K) ∫ q p dV − (1/G) ∫ (q − Πq)(p − Πp) dV = 0.
// With the pressure mass lumped (M_nn = Σ V_e/3) and e = p/K the nodal
// volumetric strain, this is the linear system
//   (M + τ S) e = B v,   τ = K/G,   (B v)_n = Σ_e V_e v_e / 3,
// S = Σ_e (V_e/36)(3 I − 1 1ᵀ) the element's ∫(N_i − ⅓)(N_j − ⅓) dV with
// ∫ N_i N_j dA = A(1 + δ_ij)/12 (V_e = 2π r̄ A). Without S (τ = 0) it is
// Bonet & Burton's (1998) average nodal pressure; S couples neighbouring
// nodes and removes what the average leaves of the locking (the spurious
// pressure modes of the unstable pair). S annihilates uniform fields, so a
// uniform strain is reproduced exactly and Σ_n M_n e_n = Σ_e V_e v_e (the
// volume is conserved globally).
//
// The system is solved each step by conjugate gradients preconditioned with
// the Cholesky factorisation of a recent matrix: the geometry changes little
// between steps, so one or two iterations reach round-off; the factorisation
// is renewed when more are needed or when the connectivity changes.
#include <span>
#include <vector>

#include <Eigen/SparseCholesky>

#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

/// The matrix c M + τ S: the lumped mass's factor c and the projection's weight τ.
struct ProjectionOperator {
  double mass_factor = 1.0;
  double weight = 0.0;
};

class PressureProjection {
 public:
  /// Per node, e solving (M + τ S) e = B v for the triangle values `values`
  /// (volumes `volumes`, m³; τ = `stabilisation_weight` ≥ 0).
  [[nodiscard]] std::vector<double> nodal_solution(std::span<const Triangle> triangles, Index node_count,
                                                   std::span<const double> volumes, double stabilisation_weight,
                                                   std::span<const double> values);
  /// x solving (c M + τ S) x = `nodal_rhs` on the nodes not `fixed` (empty:
  /// none), x = 0 on the fixed ones: the pore water's stabilised storage
  /// (docs/continuum_pile.md §6), whose drained nodes are held.
  [[nodiscard]] std::vector<double> solve(std::span<const Triangle> triangles, std::span<const double> volumes,
                                          const ProjectionOperator& op, const std::vector<bool>& fixed,
                                          std::span<const double> nodal_rhs);
  /// Conjugate-gradient iterations of the last solve (0 when the factorisation was renewed for it).
  [[nodiscard]] int last_iterations() const { return last_iterations_; }

 private:
  void factorise(std::span<const Triangle> triangles, Index node_count, std::span<const double> volumes,
                 const ProjectionOperator& op, const std::vector<bool>& fixed);

  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factorisation_;
  bool factorised_ = false;
  std::vector<Triangle> factorised_triangles_;
  Index factorised_nodes_ = 0;
  ProjectionOperator factorised_operator_;
  std::vector<bool> factorised_fixed_;
  int last_iterations_ = 0;
};

}  // namespace dfc::continuum
