#pragma once
// Kinematics of a linear axisymmetric triangle on the current geometry
// (docs/continuum_pile.md §2–§3): shape-function gradients, the velocity
// gradient with its hoop term, the rate of deformation and spin, the Jaumann
// rotation of the stress and the nodal forces of a constant stress. Pure
// functions (CONTRIBUTING.md §3), one integration point at the centroid.
//
// Tensor components in the models' SymTensor: xx = rr, yy = θθ, zz = zz,
// zx = rz (tensor shear), xy = yz = 0 (axisymmetric, no torsion).
#include <array>
#include <span>

#include <Eigen/Core>

#include "dfc/constitutive/sym_tensor.hpp"
#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

using constitutive::Stress;
using constitutive::SymTensor;
using NodalVectors = std::array<Point, 3>;

struct TriangleGeometry {
  double area = 0.0;        ///< m², positive for counter-clockwise nodes
  double centroid_r = 0.0;  ///< m
  std::array<double, 3> dn_dr{};  ///< ∂N_i/∂r, 1/m
  std::array<double, 3> dn_dz{};  ///< ∂N_i/∂z, 1/m
  /// Volume of the ring swept by the triangle about the axis, 2π r̄ A (exact for a triangle).
  [[nodiscard]] double volume() const;
};

/// The values of a nodal field at a triangle's three nodes.
[[nodiscard]] NodalVectors gather(std::span<const Point> values, const Triangle& triangle);
[[nodiscard]] TriangleGeometry triangle_geometry(const NodalVectors& corners);
/// The smallest interior angle, degrees: the shape measure of the remeshing (docs/continuum_pile.md §4).
[[nodiscard]] double smallest_angle_deg(const NodalVectors& corners);

/// ∇v in the r–z plane plus the hoop rate v_r / r at the centroid, 1/s.
struct VelocityGradient {
  double rr = 0.0, rz = 0.0, zr = 0.0, zz = 0.0;  ///< rz = ∂v_r/∂z, zr = ∂v_z/∂r
  double hoop = 0.0;
};

[[nodiscard]] VelocityGradient velocity_gradient(const TriangleGeometry& geometry, const NodalVectors& velocities);
/// D = sym ∇v, with D_θθ = v_r / r.
[[nodiscard]] SymTensor rate_of_deformation(const VelocityGradient& gradient);
/// W_rz = ½(∂v_r/∂z − ∂v_z/∂r), the only spin component in axisymmetry.
[[nodiscard]] double spin_rz(const VelocityGradient& gradient);
/// Objective update of the stress for a spin increment ω = W_rz Δt:
/// σ ← σ + (Ω σ − σ Ω), Ω the skew tensor with Ω_rz = ω (Jaumann rate).
void rotate_by_jaumann(Stress& stress, double spin_increment);
/// The nodal forces ∫ Bᵀσ dV of a constant stress (the internal forces the
/// element exerts on its nodes; the net nodal force is external − internal):
/// f_r = V (σ_rr ∂N/∂r + σ_rz ∂N/∂z + σ_θθ N/r̄), f_z = V (σ_rz ∂N/∂r + σ_zz ∂N/∂z), N = ⅓.
[[nodiscard]] NodalVectors internal_forces(const TriangleGeometry& geometry, const Stress& stress);
/// Per node, the larger of the two Gershgorin row sums Σ_j |K_ij| of the
/// element's linear elastic stiffness V BᵀDB (N/m): the bound that sizes the
/// scaled masses of an explicit step (theory/fdm.md §1.10).
[[nodiscard]] std::array<double, 3> stiffness_row_sums(const TriangleGeometry& geometry, double bulk_modulus, double shear_modulus);

}  // namespace dfc::continuum
