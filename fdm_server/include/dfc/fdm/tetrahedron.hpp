#pragma once
// Constant-strain tetrahedron kernels (docs/theory/fdm.md §1.3, §1.4, §1.7).
//
// Node n of a tetrahedron faces "face (n)", the face opposite it, with outward
// area vector a⁽ⁿ⁾ = n⁽ⁿ⁾S⁽ⁿ⁾; Σₙ a⁽ⁿ⁾ = 0 and the shape-function gradients are
// ∇Nₙ = −a⁽ⁿ⁾/(3V). These small pure functions are the physics; the solver
// only loops over them.
#include <array>
#include <span>

#include <Eigen/Core>

#include "dfc/fdm/types.hpp"

namespace dfc::fdm {

struct Tetrahedron {
  std::array<Index, 4> nodes{};  ///< gridpoint indices
  double volume = 0.0;           ///< m³, > 0 for a valid (positively oriented) tetrahedron
  std::array<Vec3, 4> area{};    ///< m², area[n] = outward area vector of the face opposite node n
};

/// Signed volume det[x₂−x₁, x₃−x₁, x₄−x₁]/6 (§1.3); positive when x₄ lies on
/// the right-hand side of the face (x₁, x₂, x₃).
[[nodiscard]] double signed_tetrahedron_volume(const Vec3& x1, const Vec3& x2, const Vec3& x3, const Vec3& x4);

/// Geometry of the tetrahedron over `nodes` with coordinates `x`. The volume
/// keeps its sign so that callers can reject inverted tetrahedra; the area
/// vectors are oriented away from the opposite node whatever the sign (§1.3:
/// a⁽ⁿ⁾·(c_face − xₙ) > 0).
[[nodiscard]] Tetrahedron make_tetrahedron(const std::array<Index, 4>& nodes, const std::array<Vec3, 4>& x);

/// Velocity gradient L_ij = v_i,j = −1/(3V) Σₙ vᵢⁿ a_jⁿ (§1.4).
[[nodiscard]] Eigen::Matrix3d velocity_gradient(const Tetrahedron& tet, std::span<const Vec3> velocity);

/// Strain rate ξ = sym(L) (§1.4); the spin ω = skew(L) is not needed in small strain.
[[nodiscard]] SymTensor strain_rate(const Tetrahedron& tet, std::span<const Vec3> velocity);

/// Force a constant-stress tetrahedron exerts on its nodes: fⁿ = ⅓ σ·a⁽ⁿ⁾ (§1.7).
/// Σₙ fⁿ·vⁿ = −V σ:ξ, so these are internal forces with the right sign (under
/// tension the nodes are pulled inwards). Multiply by the overlay weight.
[[nodiscard]] std::array<Vec3, 4> nodal_forces(const Tetrahedron& tet, const SymTensor& stress);

/// Largest face area of the tetrahedron, m² (for the timestep of §1.10).
[[nodiscard]] double largest_face_area(const Tetrahedron& tet);

}  // namespace dfc::fdm
