#pragma once
// The force and moment carried by an elastic bond disc, their incremental
// update and the peak stresses at its periphery — the machinery shared by
// linear_pbond and soft_bond (docs/theory/dem_contact_laws.md §2.3–2.5; Potyondy &
// Cundall 2004, Eqs. 8–13).
#include <cmath>

#include "dfc/dem/bond_geometry.hpp"
#include "dfc/dem/bond_increments.hpp"

namespace dfc::dem {

/// The bond disc's stiffnesses against each relative motion (dem_contact_laws.md §2.3):
/// k̄_n A, k̄_s A, k̄_s J, k̄_n I.
struct BondStiffness {
  double normal = 0.0;  ///< N/m
  double shear = 0.0;   ///< N/m
  double twist = 0.0;   ///< N m/rad
  double bend = 0.0;    ///< N m/rad

  /// From the bond's spring stiffnesses per unit area k̄_n, k̄_s [Pa/m] and its section.
  [[nodiscard]] static BondStiffness of(const BondSection& s, double kn, double ks) noexcept {
    return {kn * s.area, ks * s.area, ks * s.polar, kn * s.inertia};
  }
};

/// Bond force and moment on the first body; N > 0 in tension.
/// History layout (8 doubles from `h`): N, F_s (3), M_t, M_b (3).
struct BondLoad {
  static constexpr std::size_t history_size = 8;
  static constexpr std::size_t shear_offset = 1;  ///< of F_s in the layout, an in-plane vector
  static constexpr std::size_t bend_offset = 5;   ///< of M_b, an in-plane vector

  double normal = 0.0;  ///< N, N (tension positive)
  Vec3 shear;           ///< N, in the contact plane
  double twist = 0.0;   ///< N m, about n
  Vec3 bend;            ///< N m, in the contact plane

  /// Reads the stored load, carrying shear and bending into k's contact plane.
  [[nodiscard]] static BondLoad load(const double* h, const ContactKinematics& k) noexcept {
    const ContactTwirl twirl = ContactTwirl::of(k);
    return {h[0], load_in_plane(h + shear_offset, k.normal, twirl), h[4], load_in_plane(h + bend_offset, k.normal, twirl)};
  }
  /// Reads a stored load already carried into the current plane.
  [[nodiscard]] static BondLoad load_in_current_plane(const double* h) noexcept {
    return {h[0], load_vec3(h + shear_offset), h[4], load_vec3(h + bend_offset)};
  }
  void store(double* h) const noexcept {
    h[0] = normal;
    store_vec3(h + shear_offset, shear);
    h[4] = twist;
    store_vec3(h + bend_offset, bend);
  }
  static void clear(double* h) noexcept {
    for (std::size_t c = 0; c < history_size; ++c) h[c] = 0.0;
  }

  /// Reference §2.3: F̄_n += k̄_n A Δδ_n, F̄_s += k̄_s A Δδ_s, M̄_t += k̄_s J Δθ_t,
  /// M̄_b += k̄_n I Δθ_b (signs for tension-positive N and loads on the first
  /// body: opening stretches the springs, the second body's motion drags the first).
  void add_elastic(const BondIncrements& d, const BondStiffness& k) noexcept {
    normal += k.normal * d.normal;
    shear += k.shear * d.shear;
    twist += k.twist * d.twist;
    bend += k.bend * d.bend;
  }

  /// Force on the first body: tension pulls it towards the second (+n).
  [[nodiscard]] Vec3 force(const Vec3& n) const noexcept { return shear + normal * n; }
  [[nodiscard]] Vec3 couple(const Vec3& n) const noexcept { return bend + twist * n; }
};

/// Reference §2.4 (pbSMax): σ̄ = N/A + β̄ |M_b| R̄ / I (tension positive),
/// τ̄ = |F_s|/A + β̄ |M_t| R̄ / J; β̄ the moment-contribution factor.
struct PeakStresses {
  double tension = 0.0;  ///< Pa
  double shear = 0.0;    ///< Pa
};

[[nodiscard]] inline PeakStresses peak_stresses(const BondLoad& f, const BondSection& s, double moment_factor) noexcept {
  return {f.normal / s.area + moment_factor * norm(f.bend) * s.radius / s.inertia,
          norm(f.shear) / s.area + moment_factor * std::abs(f.twist) * s.radius / s.polar};
}

/// Reference §2.5 (pbShearStrength): τ̄_c = c̄ - σ tan φ̄ with σ = N/A
/// (tension positive) capped at the tensile strength σ̄_c; never below 0.
[[nodiscard]] inline double shear_strength(double mean_normal_stress, double cohesion, double tan_friction_angle, double tensile_strength) noexcept {
  const double sigma = std::min(mean_normal_stress, tensile_strength);
  return std::max(0.0, cohesion - sigma * tan_friction_angle);
}

/// True when neither peak stress can reach its limit, decided without a
/// square root and with one division: |v| <= |v_x| + |v_y| + |v_z| bounds both
/// peaks from above, and since R̄/I = 4/(A R̄) and R̄/J = 2/(A R̄) the stresses
/// and limits are compared multiplied by A (A σ̄ <= N + 4 β̄ |M_b|₁ / R̄,
/// A τ̄ <= |F_s|₁ + 2 β̄ |M_t| / R̄, A τ̄_c = max(0, c̄ A − min(N, σ̄_c A) tan φ̄)).
/// Most intact bonds are far from failure, so the exact test (peak_stresses,
/// shear_strength) runs only for the others (measured: +3 % bonded throughput
/// on the peer benchmark, where no bond is near failure).
/// per_radius = β̄ / R̄, tension_limit = σ̄_c A, cohesion_force = c̄ A (pair
/// constants of the law: no division per step).
[[nodiscard]] inline bool surely_below_limits(const BondLoad& f, double per_radius, double tension_limit, double cohesion_force,
                                              double tan_friction_angle) noexcept {
  const double bend = std::abs(f.bend.x) + std::abs(f.bend.y) + std::abs(f.bend.z);
  if (f.normal + 4.0 * per_radius * bend >= tension_limit) return false;
  const double shear = std::abs(f.shear.x) + std::abs(f.shear.y) + std::abs(f.shear.z) + 2.0 * per_radius * std::abs(f.twist);
  return shear < std::max(0.0, cohesion_force - std::min(f.normal, tension_limit) * tan_friction_angle);
}

}  // namespace dfc::dem
