#pragma once
// The symmetric second-order tensor of the constitutive models (stress, strain
// and their increments), shared by fdm_server and continuum_server. Tension
// and extension positive (docs/theory/README.md, "Sign conventions").
#include <array>
#include <cmath>

#include <Eigen/Core>

namespace dfc::constitutive {

using Vec3 = Eigen::Vector3d;

/// Symmetric 3×3 tensor stored as (xx, yy, zz, xy, yz, zx).
/// Shear components are tensor components (ε_xy, not the engineering γ_xy = 2ε_xy).
struct SymTensor {
  double xx = 0.0, yy = 0.0, zz = 0.0, xy = 0.0, yz = 0.0, zx = 0.0;

  [[nodiscard]] static SymTensor isotropic(double value) { return {value, value, value, 0.0, 0.0, 0.0}; }
  /// sym(m) = (m + mᵀ)/2.
  [[nodiscard]] static SymTensor symmetric_part(const Eigen::Matrix3d& m) {
    return {m(0, 0), m(1, 1), m(2, 2), 0.5 * (m(0, 1) + m(1, 0)), 0.5 * (m(1, 2) + m(2, 1)), 0.5 * (m(2, 0) + m(0, 2))};
  }

  [[nodiscard]] double trace() const { return xx + yy + zz; }
  [[nodiscard]] SymTensor deviator() const {
    const double mean = trace() / 3.0;
    return {xx - mean, yy - mean, zz - mean, xy, yz, zx};
  }
  /// The tensor applied to a vector: (σ·a)_i = σ_ij a_j.
  [[nodiscard]] Vec3 apply(const Vec3& a) const {
    return {xx * a.x() + xy * a.y() + zx * a.z(), xy * a.x() + yy * a.y() + yz * a.z(), zx * a.x() + yz * a.y() + zz * a.z()};
  }
  [[nodiscard]] std::array<double, 6> components() const { return {xx, yy, zz, xy, yz, zx}; }
  /// The full 3×3 matrix.
  [[nodiscard]] Eigen::Matrix3d matrix() const {
    Eigen::Matrix3d m;
    m << xx, xy, zx, xy, yy, yz, zx, yz, zz;
    return m;
  }
  /// Frobenius norm √(a_ij a_ij), shear components counted twice.
  [[nodiscard]] double norm() const { return std::sqrt(xx * xx + yy * yy + zz * zz + 2.0 * (xy * xy + yz * yz + zx * zx)); }
  /// The normal component n·σ·n along a unit vector n.
  [[nodiscard]] double normal_component(const Vec3& n) const { return n.dot(apply(n)); }

  SymTensor& operator+=(const SymTensor& o) {
    xx += o.xx, yy += o.yy, zz += o.zz, xy += o.xy, yz += o.yz, zx += o.zx;
    return *this;
  }
  SymTensor& operator*=(double s) {
    xx *= s, yy *= s, zz *= s, xy *= s, yz *= s, zx *= s;
    return *this;
  }
  SymTensor& operator-=(const SymTensor& o) {
    xx -= o.xx, yy -= o.yy, zz -= o.zz, xy -= o.xy, yz -= o.yz, zx -= o.zx;
    return *this;
  }
  [[nodiscard]] friend SymTensor operator+(SymTensor a, const SymTensor& b) { return a += b; }
  [[nodiscard]] friend SymTensor operator-(SymTensor a, const SymTensor& b) { return a -= b; }
  [[nodiscard]] friend SymTensor operator*(SymTensor a, double s) { return a *= s; }
  [[nodiscard]] friend SymTensor operator*(double s, SymTensor a) { return a *= s; }
};

using Stress = SymTensor;  ///< Pa, tension positive

}  // namespace dfc::constitutive
