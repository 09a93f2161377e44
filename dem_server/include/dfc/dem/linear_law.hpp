#pragma once
// `linear`: the PFC linear contact model, unbonded and frictional
// (Itasca PFC 6/7 "Linear Model"; Cundall & Strack 1979; docs/theory/dem_contact_laws.md §2.3).
//
//   normal:  F_n = k_n * overlap (compression positive, no tension)
//            + dashpot F_d = -2 beta_n sqrt(m_eff k_n) v_n (PFC dp_nratio, full mode)
//   shear:   F_s <- rotate(F_s) + k_s * dU_s,  dU_s = v_t dt   (incremental)
//            |F_s| <= mu * F_n                                   (Coulomb slip)
//            + dashpot 2 beta_s sqrt(m_eff k_s) v_t while not sliding (PFC dp_sratio)
//
// Dashpots: c = 2 beta sqrt(m k) (docs/theory/dem_contact_laws.md §2.3, dashpots).
// The normal one acts always (PFC "full" normal mode). The shear one is cut
// while the contact slides (PFC dp_mode 2, "slip-cut" shear), so a sliding
// contact carries mu F_n and no more, as in LAMMPS's gran/hooke/history and
// LIGGGHTS's hooke/stiffness (they cap spring + dashpot together). PFC's
// default full shear mode would add c_s v_t on top of mu F_n: measured on the
// peer benchmark (docs/dem_benchmarks.md), that dissipates visibly more than
// the peers do, where the slip-cut form matches them.
//
// History: the shear spring force on the first body, 3 components in global
// axes, rotated with the contact plane every step (the dashpot has no memory).
#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "dfc/dem/contact_model.hpp"
#include "dfc/dem/contact_plane_rotation.hpp"

namespace dfc::dem {

struct LinearLaw {
  static constexpr std::string_view keyword = "linear";
  static constexpr std::size_t history_size = 3;
  static constexpr bool has_couple = false;
  static constexpr bool acts_across_gap = false;
  static constexpr bool bonded = false;

  double kn = 0.0;                    ///< N/m
  double ks = 0.0;                    ///< N/m
  double friction = 0.0;              ///< -
  double damping_ratio_normal = 0.0;  ///< - (fraction of critical)
  double damping_ratio_shear = 0.0;   ///< - (fraction of critical)

  [[nodiscard]] static std::vector<HistoryColumn> history_columns();
  [[nodiscard]] static LinearLaw from_parameters(const LawParameters& values);

  [[nodiscard]] StiffnessBound stiffness_bound(double /*radius_max*/) const noexcept { return {kn, ks}; }

  void separate(double* history) const noexcept { history[0] = history[1] = history[2] = 0.0; }

  /// Pair constants (contact_model.hpp HasPairConstants): [0] = -c_n, the
  /// normal dashpot coefficient c_n = 2 beta_n sqrt(m_eff k_n) negated, and
  /// [1] = c_s = 2 beta_s sqrt(m_eff k_s) (docs/theory/dem_contact_laws.md §2.3), in N s/m.
  static constexpr std::size_t constants_size = 2;
  void pair_constants(const ContactKinematics& k, double* c) const noexcept {
    c[0] = damping_ratio_normal > 0.0 ? -2.0 * damping_ratio_normal * std::sqrt(k.effective_mass * kn) : 0.0;
    c[1] = damping_ratio_shear > 0.0 ? 2.0 * damping_ratio_shear * std::sqrt(k.effective_mass * ks) : 0.0;
  }

  [[nodiscard]] ContactForce evaluate(const ContactKinematics& k, double* history) const noexcept {
    double c[constants_size];
    pair_constants(k, c);
    return evaluate(k, c, history);
  }

  /// The shear force turns with the contact plane (RotatesInPlaneHistory).
  static constexpr std::array<std::size_t, 1> in_plane_history{0};

  [[nodiscard]] ContactForce evaluate(const ContactKinematics& k, const double* constants, double* history) const noexcept {
    rotate_in_plane_history<LinearLaw>(history, k);
    return evaluate_in_plane(k, constants, history);
  }

  /// evaluate() for a history already carried into k's contact plane.
  [[nodiscard]] ContactForce evaluate_in_plane(const ContactKinematics& k, const double* constants, double* history) const noexcept {
    const Vec3& n = k.normal;
    const double fn_spring = kn * k.overlap;  // compression positive; overlap > 0 here, so never tensile
    const double vn = dot(k.relative_velocity, n);  // > 0 opening
    // Like PFC's default full mode the dashpot may make the total normal force tensile while opening.
    const double fn_dashpot = damping_ratio_normal > 0.0 ? constants[0] * vn : 0.0;

    Vec3 shear = load_vec3(history);
    // The second body's contact point moving by v_t dt drags the first body along v_t.
    const Vec3 tangential_velocity = k.relative_velocity - vn * n;
    shear += (ks * k.dt) * tangential_velocity;
    // Coulomb slip: |F_s| capped at mu F_n, its direction kept. The same test
    // cuts the shear dashpot below.
    const double limit = friction * fn_spring;
    const double magnitude2 = norm2(shear);
    const bool sliding = magnitude2 > limit * limit;
    if (sliding) shear = (limit / std::sqrt(magnitude2)) * shear;
    history[0] = shear.x;
    history[1] = shear.y;
    history[2] = shear.z;
    // The normal force pushes the first body away from the second: along -n.
    Vec3 on_first = shear - (fn_spring + fn_dashpot) * n;
    // The shear dashpot drags the first body along v_t too, unless it slides (slip-cut).
    if (damping_ratio_shear > 0.0 && !sliding) on_first += constants[1] * tangential_velocity;
    return {on_first, {}};
  }
};

static_assert(RotatesInPlaneHistory<LinearLaw>);

}  // namespace dfc::dem
