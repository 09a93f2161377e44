#pragma once
// The stiffness matrix of the FDM's own discretization, for an implicit static
// solve on the same zones (docs/theory/coupling.md §1, reference continuum).
//
// Each hexahedral zone is the fdm_server's two overlays of five constant-strain
// tetrahedra (docs/theory/fdm.md §1.2), each tetrahedron weighted ½ (§1.7), with the
// volumetric strain averaged over the zone's ten tetrahedra (mixed
// discretization, §1.5). For isotropic elasticity the explicit solver's
// internal gridpoint forces are then exactly f_int = −K u with
//   K = Σ_zones ½ [ Σ_t V_t B_tᵀ D_dev B_t + K_bulk w wᵀ / Σ_t V_t ],
// where B_t is the tetrahedron's strain operator (∇Nₙ = −a⁽ⁿ⁾/(3V), §1.3–§1.4),
// D_dev = 2G(I − ⅓ 1⊗1) the deviatoric Hooke operator and w = Σ_t V_t ∇N_t the
// volume-weighted divergence operator of the zone (a B-bar element). So the
// static solution of K u = f is the state the explicit solver relaxes to.
#include <cstddef>
#include <span>

#include <Eigen/SparseCore>

#include "dfc/constitutive/constitutive_model.hpp"
#include "dfc/fdm/tetrahedron.hpp"

namespace dfc::reference {

/// K (3N × 3N, degree of freedom 3·gridpoint + component) of `tetrahedra`,
/// given zone-major with fdm::kTetrahedraPerZone per zone (fdm::Solver::tetrahedra()).
[[nodiscard]] Eigen::SparseMatrix<double> assemble_elastic_stiffness(std::span<const fdm::Tetrahedron> tetrahedra,
                                                                     std::size_t gridpoint_count, const constitutive::ElasticModuli& moduli);

}  // namespace dfc::reference
