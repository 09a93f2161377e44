#pragma once
// Darcy flow between the nodes of linear axisymmetric triangles
// (docs/continuum_pile.md §6): the Galerkin conductance of the fluid mass
// balance, H_ij = Σ_e V_e (k/γ_w) ∇N_i·∇N_j (exact for linear triangles with
// V_e = 2π r̄ A), so that the water volume leaving node i per second is
// (H p)_i; and the stable explicit step it allows with a lumped storage.
#include <span>
#include <vector>

#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

/// Per node, (H p)_i, m³/s: the water volume flowing out of the node's
/// share of the body per second (Σ_i (H p)_i = 0: flow only moves water).
[[nodiscard]] std::vector<double> darcy_outflow(std::span<const Point> nodes, std::span<const Triangle> triangles,
                                                double mobility, std::span<const double> pore_pressures);
/// Per node, Σ_j |H_ij|, m³/(Pa s): the Gershgorin bound of the conductance's rows.
[[nodiscard]] std::vector<double> darcy_row_sums(std::span<const Point> nodes, std::span<const Triangle> triangles, double mobility);
/// The largest stable forward-Euler step of C ṗ = −H p with the lumped
/// storage C_i (m³/Pa), s: 2 min_i C_i / Σ_j |H_ij| over the nodes
/// `free_nodes` (true where p is not held). For a uniform 1-D column of
/// spacing h it is h²/(2 c), c = k M_w/γ_w the diffusivity of the water alone.
[[nodiscard]] double stable_flow_step(std::span<const double> storage, std::span<const double> row_sums, const std::vector<bool>& free_nodes);

}  // namespace dfc::continuum
