#pragma once
// `damage_bond`: the Zheng–Ciantia damage-plasticity bond for porous soft
// rock (Zheng & Ciantia 2025, RMRE, doi 10.1007/s00603-025-04411-0;
// docs/theory/dem_contact_laws.md §3; Ciantia et al. 2024 §2.1 Eqs. 1–2, Table 1).
// Implemented from the equations only (no code taken from the authors' implementation).
//
//   forces (guide Eq. 1, total form; equal to the code's incremental update
//   with damaged stiffnesses, §3.1):
//     N = (1-D) k̄_n A (u_n - u_n^p),  V = (1-D) k̄_s A (u_s - u_s^p),
//     M_b = (1-D) k̄_n I (θ_b - θ_b^p),  M_t = (1-D) k̄_s J θ_t (elastic, §3.1)
//     k̄_n = Ē*/(R1+R2), k̄_s = k̄_n/κ̄*, R̄ = λ R_min (§2.1–2.2)
//   capacities (guide Eq. 4, §3.3): [N̄, V̄, M̃] = [σ_0 A, C A, σ_t I/R̄²](1-D),
//     σ_0 = σ_t in tension, σ_c in compression (asymmetric envelope)
//   envelope (Ciantia et al. 2024 Eq. 1, §3.2): damage_envelope.hpp
//   damage (guide Eq. 2, not Ciantia et al. 2024 Eq. 2 as printed; §3.4: each plastic
//   measure over its own characteristic value):
//     D = 1 - exp(-(ū_n^p/u_cn + ū_s^p/u_cs + θ̄_b^p/θ_c))
//     with ū^p the ACCUMULATED plastic measures Σ|Δu^p| (equal to |u^p| on a
//     monotonic path; on cyclic paths they keep D non-decreasing, which |u^p|
//     would not); D is also never lowered.
//   breakage (§3.6): D > 0.99; then the linear frictional contact alone.
//   linear contact (§3.6): k_n = π E* R_min²/(R1+R2), k_s = k_n/κ*, friction μ,
//     acting in parallel once D > 0 and the surfaces overlap; not while intact.
//
// Why the return needs no iteration on D: N and N̄ (and V, V̄ and M̆, M̃)
// carry the same factor (1-D), so N/N̄ = k̄_n (u_n - u_n^p)/σ_0 depends on the
// elastic displacements only. The return is then a closest-point projection
// in these normalised coordinates with the energy-norm weights
//   w = (σ_0²/k̄_n, C²/k̄_s, σ_t²/(4 k̄_n))   (common factor A(1-D) dropped;
//   I/R̄² = A/4), after which D follows explicitly from the plastic measures.
//
// Breakage label: broken_tension when N >= 0 and the normal plastic measure
// is the largest term of the damage exponent; broken_shear otherwise (shear,
// bending and compressive crushing).
//
// History (23): state, D, u_n, u_s (3), θ_t, θ_b (3), u_n^p, u_s^p (3),
// θ_b^p (3), ū_n^p, ū_s^p, θ̄_b^p, linear shear force (3).
#include <span>
#include <string_view>
#include <vector>

#include "dfc/dem/bond_geometry.hpp"
#include "dfc/dem/bond_increments.hpp"
#include "dfc/dem/bond_state.hpp"
#include "dfc/dem/damage_envelope.hpp"
#include "dfc/dem/linear_law.hpp"

namespace dfc::dem {

struct DamageBondLaw {
  static constexpr std::string_view keyword = "damage_bond";
  enum Column : std::size_t {
    state = 0, damage = 1, opening = 2, slip = 3, twist = 6, bend = 7,
    plastic_opening = 10, plastic_slip = 11, plastic_bend = 14,
    accumulated_opening = 17, accumulated_slip = 18, accumulated_bend = 19, linear_shear = 20,
  };
  static constexpr std::size_t history_size = 23;
  static constexpr bool has_couple = true;
  static constexpr bool acts_across_gap = true;
  static constexpr bool bonded = true;
  /// While intact the force is (1-D) k A (u - u^p) from stored displacements
  /// alone (the linear contact is off): scaling them scales the load (stress_scaling.hpp).
  static constexpr bool intact_force_from_history = true;
  static constexpr double breakage_damage = 0.99;  ///< dem_contact_laws.md §3.6

  double emod = 0.0;                  ///< Pa, E* (linear contact)
  double kratio = 1.0;                ///< -, κ*
  double friction = 0.5;              ///< -, μ
  double damping_ratio_normal = 0.0;  ///< - (linear contact)
  double bond_emod = 0.0;             ///< Pa, Ē*
  double bond_kratio = 1.0;           ///< -, κ̄*
  double radius_multiplier = 1.0;     ///< -, λ
  double tensile_strength = 0.0;      ///< Pa, σ_t
  double compressive_strength = 0.0;  ///< Pa, σ_c
  double cohesion = 0.0;              ///< Pa, C
  double u_cn = 0.0;                  ///< m, normal softening length
  double u_cs = 0.0;                  ///< m, shear softening length
  double theta_c = 0.0;               ///< rad, bending softening rotation
  double bond_gap = 0.0;              ///< m
  double damping_ratio_shear = 0.0;   ///< - (linear contact; linear_law.hpp: cut while it slides)

  [[nodiscard]] static std::vector<HistoryColumn> history_columns();
  [[nodiscard]] static DamageBondLaw from_parameters(const LawParameters& values);

  [[nodiscard]] StiffnessBound stiffness_bound(double radius_max) const noexcept {
    const double kn = deformability_kn_bound(emod, radius_max);
    const double kbn = deformability_kn_bound(bond_emod, radius_max) * radius_multiplier * radius_multiplier;
    return {kn + kbn, kn / kratio + kbn / bond_kratio};
  }

  void separate(double* history) const noexcept { store_vec3(history + linear_shear, {}); }

  /// D of the corrected Eq. 2 from the accumulated plastic measures.
  [[nodiscard]] double damage_from(double opening_p, double slip_p, double bend_p) const noexcept;

  /// Elastic trial, return to the envelope, damage and breakage of a bonded
  /// contact; returns the bond's force and couple on the first body.
  [[nodiscard]] ContactForce update_bond(const ContactKinematics& k, double* history) const noexcept;

  /// Adds `force` (on the first body) to a bonded contact's load through its
  /// elastic displacements: Δu_n = ΔN/((1-D) k̄_n A), Δu_s = ΔV/((1-D) k̄_s A)
  /// (Eq. 1), so the bond holds a state it could have reached elastically
  /// (seam balance, seam_balance.hpp). The envelope is checked at the next evaluation.
  void add_bond_load(double* history, const ContactKinematics& k, const Vec3& force) const noexcept {
    const double area = bond_section(k, radius_multiplier).area;
    const double kn = deformability_bond_kn(k, bond_emod), ks = kn / bond_kratio, intact = 1.0 - history[damage];
    const double normal = dot(force, k.normal);
    history[opening] += normal / (intact * kn * area);
    store_vec3(history + slip, load_in_plane(history + slip, k.normal, ContactTwirl::of(k)) + (1.0 / (intact * ks * area)) * (force - normal * k.normal));
  }

  [[nodiscard]] ContactForce evaluate(const ContactKinematics& k, double* history) const noexcept {
    ContactForce out{};
    const BondState s = bond_state(history);
    if (is_bonded(s)) out = update_bond(k, history);
    // The linear contact acts once the bond is damaged or gone (§3.6).
    if (bond_state(history) == BondState::intact || k.overlap <= 0.0) {
      separate(history);
      return out;
    }
    const double kn = deformability_kn(k, emod);
    const LinearLaw linear{.kn = kn, .ks = kn / kratio, .friction = friction, .damping_ratio_normal = damping_ratio_normal,
                           .damping_ratio_shear = damping_ratio_shear};
    out.on_first += linear.evaluate(k, history + linear_shear).on_first;
    return out;
  }
};

static_assert(ContactLawKernel<DamageBondLaw>);

}  // namespace dfc::dem
