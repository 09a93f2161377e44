#pragma once
// PeriodicCell: an axis-aligned box whose faces may be periodic per axis, and
// which deforms homogeneously with a per-axis strain rate (docs/dem_periodic.md).
//
// Periodic axes: a particle that leaves through one face re-enters through the
// opposite one (wrap, at each neighbour-list rebuild), and the branch vector
// between two centres is the minimum image (Allen & Tildesley, Computer
// Simulation of Liquids, 2nd ed. 2017, §1.6.2): d_a -= L_a nint(d_a / L_a).
// It is unique for every pair that can touch as long as each periodic edge is
// at least 2 (2 r_max + skin) long (checked where the cell is set up and at
// every rebuild).
//
// Deformation (like LAMMPS fix deform "remap x"): each step every edge length
// is multiplied by (1 + rate_a dt) about the cell centre c, and so is every
// particle coordinate: x_a <- c_a + (1 + rate_a dt)(x_a - c_a). Velocities are
// not remapped; they stay the fluctuation about the homogeneous flow, so the
// contact kernels add the affine relative velocity rate_a d_a to every pair
// (PeriodicSpace below): incremental (bond) laws then see the imposed strain.
#include <array>
#include <cmath>
#include <span>

#include "dfc/dem/vec3.hpp"

namespace dfc::dem {

struct PeriodicCell {
  Vec3 lo;                                ///< m, lower corner
  Vec3 hi;                                ///< m, upper corner
  std::array<bool, 3> periodic{true, true, true};
  Vec3 strain_rate;                       ///< 1/s, rate of each edge, dL_a/dt / L_a (extension positive)

  [[nodiscard]] Vec3 length() const noexcept { return hi - lo; }
  [[nodiscard]] Vec3 centre() const noexcept { return 0.5 * (lo + hi); }
  [[nodiscard]] double volume() const noexcept {
    const Vec3 l = length();
    return l.x * l.y * l.z;
  }
  [[nodiscard]] bool any_periodic() const noexcept { return periodic[0] || periodic[1] || periodic[2]; }
  /// The coordinate of x on every periodic axis brought into [lo, hi).
  [[nodiscard]] Vec3 wrap(const Vec3& x) const noexcept;
  /// Minimum image of a difference vector on the periodic axes (|d_a| < 1.5 L_a).
  [[nodiscard]] Vec3 minimum_image(const Vec3& d) const noexcept;
  /// Applies one step of strain_rate: the edges and every point of `points`
  /// (positions, the Verlet reference positions) are stretched about the centre,
  /// on up to `threads` threads.
  void deform(double dt, std::span<Vec3> positions, std::span<Vec3> references, int threads = 1) noexcept;
};

/// Branch vector and affine velocity of the open (non-periodic) space: the
/// contact kernels compiled with it are the original ones, instruction for
/// instruction (the non-periodic path pays nothing for the periodic one).
struct OpenSpace {
  static constexpr bool periodic = false;
  [[nodiscard]] static Vec3 branch(const Vec3& xi, const Vec3& xj) noexcept { return xj - xi; }
};

/// The same for a periodic cell: the minimum image by one compare-and-shift
/// per axis (half_length is +inf on open axes, so nothing shifts there). Two
/// centres are never more than 1.5 edges apart along a periodic axis (both are
/// wrapped into the cell at every rebuild and move less than a skin between
/// rebuilds), so one shift is the nearest image: the same result as
/// d_a - L_a nint(d_a / L_a), without a call to nearbyint per axis and pair
/// (a libm call without SSE4.1: removing it raised the peer benchmark's
/// throughput by 20 %, docs/dem_benchmarks.md).
struct PeriodicSpace {
  static constexpr bool periodic = true;
  Vec3 length;          ///< m, edge lengths
  Vec3 half_length;     ///< m, L/2 on periodic axes, +inf on open ones
  Vec3 strain_rate;     ///< 1/s

  PeriodicSpace();  ///< no periodic axis
  explicit PeriodicSpace(const PeriodicCell& cell) noexcept;
  /// Requires |x_j - x_i| < 1.5 L on every periodic axis.
  [[nodiscard]] Vec3 branch(const Vec3& xi, const Vec3& xj) const noexcept {
    const Vec3 d = xj - xi;
    return {nearest(d.x, length.x, half_length.x), nearest(d.y, length.y, half_length.y), nearest(d.z, length.z, half_length.z)};
  }
  /// m/s, velocity of the homogeneous flow at branch d relative to its start.
  [[nodiscard]] Vec3 affine_velocity(const Vec3& d) const noexcept {
    return {strain_rate.x * d.x, strain_rate.y * d.y, strain_rate.z * d.z};
  }

 private:
  [[nodiscard]] static double nearest(double d, double l, double half) noexcept { return d > half ? d - l : (d < -half ? d + l : d); }
};

}  // namespace dfc::dem
