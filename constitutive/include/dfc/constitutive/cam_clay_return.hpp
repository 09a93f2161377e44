#pragma once
// Kernels of the structured (bonded) Modified Cam Clay of Ciantia et al. 2024 §2.2
// (Monforte et al. 2019; docs/theory/fdm.md §3), in triaxial invariants,
// COMPRESSION POSITIVE: p = −tr(σ)/3, q = √(3/2)‖dev σ‖, ε_v^p = −tr(Δε^p),
// ε_q^p = √(2/3)‖dev Δε^p‖.
//
//   yield     f = (q/M_f)² + (p + p_t)(p + p_t − p_c),   p_c = p_s + (1 + k) p_t     (§3.2)
//   potential g = (q/M_g)² + (p + p_t)(p + p_t − p_c)                                (§3.2, inferred form)
//   hardening p_s = p_s,n exp[ρ_s(Δε_v^p + ξ_s Δε_q^p)]                              (§3.3, sign chosen, see below)
//   debonding p_t = p_t,n exp[−ρ_t(|Δε_v^p| + ξ_t Δε_q^p)]                            (§3.3, sign chosen, see below)
//
// Unconfirmed details and the choices made (docs/fdm_models.md lists them):
//  * M_g: the authors' open-source Kratos implementation has only associative flow in its
//    code; Ciantia et al. 2024 say "M_f controls the shape of the yield surface while
//    M_g controls the plastic flow". g is the yield function with M_f replaced
//    by M_g (the form §3.2 suggests), so g and f share the p-axis intercepts
//    and the critical state (∂g/∂p = 0 at the ellipse top), and M_g only
//    rotates the flow vector towards less (M_g > M_f) deviatoric flow.
//  * Signs: Table 2 lists ρ_t = +15 while Ciantia et al. 2024 describe bond degradation,
//    so p_t must DECREASE with plastic strain for ρ_t > 0: the Nova-type sign
//    ṗ_t = −ρ_t p_t(...) is used, not the Kratos one (which needs ρ_t < 0,
//    §3.3 "Sign caveat"). For p_s the same Nova-type convention is used,
//    ṗ_s = +ρ_s p_s(ε̇_v^p + ξ_s ε̇_q^p): with Table 2 (ξ_s = 0.5) this gives a
//    drained residual stress ratio q/p = 1.41 (φ ≈ 35°, plausible for
//    destructured chalk) where the Kratos sign (−ξ_s) gives 0.71 (φ ≈ 19°).
//    A negative ξ_s or ρ_t reproduces the Kratos signs.
//  * k (Kratos KSIM) is not in Table 2; it defaults to 0 (bonding adds tensile
//    strength p_t and enlarges the ellipse only on the tension side).
//
// The return mapping is fully implicit (backward Euler, the flow direction at
// the final state) in two unknowns, u = Δε_v^p and w = Δε_q^p, with
//   p = p^tr − K u,  q = q^tr − 3G w,
//   R1 = f(p, q, p_s(u,w), p_t(u,w)) = 0,
//   R2 = u ∂g/∂q − w ∂g/∂p = 0     (the plastic strain is parallel to ∇g),
// solved by Newton's method with the analytical Jacobian. Elasticity is linear
// (Table 2 gives E and ν only), so the deviatoric direction of the trial
// stress is kept (radial return in the deviatoric plane).
#include <optional>

#include "dfc/constitutive/constitutive_model.hpp"

namespace dfc::constitutive {

struct StructuredCamClayParameters {
  ElasticModuli moduli;
  double ps0 = 0.0;    ///< initial p_s (unbonded preconsolidation), Pa, > 0
  double pt0 = 0.0;    ///< initial p_t (bonding, tensile strength), Pa, >= 0
  double mf = 1.0;     ///< M_f, slope controlling the yield-surface shape, > 0
  double mg = 1.0;     ///< M_g, slope of the plastic potential, > 0
  double rho_s = 0.0;  ///< ρ_s, volumetric hardening rate of p_s, -
  double rho_t = 0.0;  ///< ρ_t, debonding rate of p_t, -
  double xi_s = 0.0;   ///< ξ_s, weight of deviatoric plastic strain in the p_s law, -
  double xi_t = 0.0;   ///< ξ_t, weight of deviatoric plastic strain in the p_t law, -
  double k = 0.0;      ///< k of p_c = p_s + (1+k) p_t, >= 0
};

/// The hardening variables of one material point, Pa.
struct CamClayHardening {
  double ps = 0.0;
  double pt = 0.0;
};

/// f of §3.2 (Pa²; > 0 outside the surface).
[[nodiscard]] double cam_clay_yield(double p, double q, const CamClayHardening& h, const StructuredCamClayParameters& m);

/// The hardening variables after plastic strain increments (u, w): the
/// exponential laws above, exact for the incremental form of §3.3.
[[nodiscard]] CamClayHardening cam_clay_hardened(const CamClayHardening& h, double u, double w, const StructuredCamClayParameters& m);

struct CamClayReturn {
  double p = 0.0;  ///< Pa
  double q = 0.0;  ///< Pa, >= 0
  double u = 0.0;  ///< Δε_v^p (compression positive)
  double w = 0.0;  ///< Δε_q^p >= 0
  CamClayHardening hardening;
};

/// Implicit return from the trial invariants (f(p_tr, q_tr) > 0 assumed).
/// nullopt when Newton's method does not converge (the caller sub-steps).
[[nodiscard]] std::optional<CamClayReturn> cam_clay_return(double p_trial, double q_trial, const CamClayHardening& h,
                                                           const StructuredCamClayParameters& m);

/// The q at which a stress path p = p0 + q/slope from (p0, 0) meets the yield
/// surface (drained triaxial: slope 3), Pa; for hand calculations and tests.
[[nodiscard]] double cam_clay_yield_q_on_path(double p0, double slope, const CamClayHardening& h, const StructuredCamClayParameters& m);

}  // namespace dfc::constitutive
