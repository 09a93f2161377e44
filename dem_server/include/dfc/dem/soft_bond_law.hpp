#pragma once
// `soft_bond`: a bond that softens in tension and fails brittly in shear
// (Itasca PFC softbond, docs/theory/dem_contact_laws.md §1; parameters of Zheng et al. 2023
// Table 2: E* 2.8 GPa, κ* 2.4, c 0.45 MPa, σ_t 0.45 MPa, φ 32°, ζ 100, γ 0.05).
//
// Itasca's force–displacement equations are [not found] (dem_contact_laws.md §1.2).
// This implements the INFERRED form of §1.2, documented in docs/dem_bond_laws.md:
//  - one set of stiffnesses for bonded and unbonded states (§1.1):
//    k_n = E*/(R1+R2) [Pa/m] over the bond disc A = π(λ R_min)², k_s = k_n/κ*;
//  - while bonded, incremental N, F_s, M_t, M_b as the parallel bond (§2.3),
//    carrying tension and compression; peak stresses as §2.4;
//  - peripheral elongation e, with de = Δδ_n + β R̄ Δ|M_b| / (k_n I): in the
//    elastic range σ = k_n e exactly (both terms grow σ by k_n de);
//  - tension: elastic up to σ_t (at e = u_c = σ_t/k_n); beyond, the bond is
//    "damaged" and the peripheral stress is capped by the linear softening
//    line σ_s(e_max) = σ_t - (k_n/ζ)(e_max - u_c), e_max the largest e reached
//    (the [unconfirmed] Ma & Huang 2018 slope -k_n/ζ). Above the cap, the
//    tensile N (if N > 0) and M_b are scaled by a common factor down to it;
//    unloading and reloading below the cap are elastic with k_n;
//  - the bond breaks in tension when σ_s <= γ σ_t, i.e. when
//    e_max >= u_c (1 + ζ (1 - γ)); ζ = 0 gives brittle tensile failure;
//  - shear: brittle, τ = |F_s|/A + β|M_t|R̄/J >= c - σ tan φ (σ = N/A);
//  - after breakage: no-tension linear contact with k_n A, k_s A and
//    Coulomb friction μ (the Jiang 2015 rolling and twisting resistance of
//    Itasca's unbonded softbond is not implemented).
//
// History (14): state, BondLoad (8), e, e_max, linear shear force (3).
#include <algorithm>
#include <span>
#include <string_view>
#include <vector>

#include "dfc/dem/bond_state.hpp"
#include "dfc/dem/linear_law.hpp"
#include "dfc/dem/parallel_bond_forces.hpp"

namespace dfc::dem {

struct SoftBondLaw {
  static constexpr std::string_view keyword = "soft_bond";
  static constexpr std::size_t load_offset = 1;
  static constexpr std::size_t elongation_column = load_offset + BondLoad::history_size;
  static constexpr std::size_t max_elongation_column = elongation_column + 1;
  static constexpr std::size_t linear_offset = max_elongation_column + 1;
  static constexpr std::size_t history_size = linear_offset + LinearLaw::history_size;
  static constexpr bool has_couple = true;
  static constexpr bool acts_across_gap = true;
  static constexpr bool bonded = true;
  /// While intact the force and couple are the stored BondLoad alone (no
  /// overlap term): scaling the stored columns scales the load (stress_scaling.hpp).
  static constexpr bool intact_force_from_history = true;

  double emod = 0.0;                  ///< Pa, E*
  double kratio = 1.0;                ///< -, κ*
  double friction = 0.5;              ///< -, μ of the unbonded contact
  double damping_ratio_normal = 0.0;  ///< - (unbonded contact)
  double radius_multiplier = 1.0;     ///< -, λ
  double moment_factor = 1.0;         ///< -, β
  double tensile_strength = 0.0;      ///< Pa, σ_t
  double cohesion = 0.0;              ///< Pa, c
  double tan_friction_angle = 0.0;    ///< -, tan φ
  double softening_factor = 0.0;      ///< -, ζ
  double cut_factor = 0.0;            ///< -, γ
  double bond_gap = 0.0;              ///< m
  double damping_ratio_shear = 0.0;   ///< - (unbonded contact; linear_law.hpp: cut while it slides)

  [[nodiscard]] static std::vector<HistoryColumn> history_columns();
  [[nodiscard]] static SoftBondLaw from_parameters(const LawParameters& values);

  [[nodiscard]] StiffnessBound stiffness_bound(double radius_max) const noexcept {
    const double kn = deformability_kn_bound(emod, radius_max) * radius_multiplier * radius_multiplier;
    return {kn, kn / kratio};
  }

  void separate(double* history) const noexcept {
    for (std::size_t c = linear_offset; c < history_size; ++c) history[c] = 0.0;
  }

  /// Elongation at which the softened strength reaches γ σ_t (bond removed).
  [[nodiscard]] double breaking_elongation(double kn) const noexcept {
    return tensile_strength / kn * (1.0 + softening_factor * (1.0 - cut_factor));
  }
  /// Cap of the peripheral tensile stress after the largest elongation e_max.
  [[nodiscard]] double softened_strength(double kn, double max_elongation) const noexcept {
    const double peak_elongation = tensile_strength / kn;
    if (max_elongation <= peak_elongation) return tensile_strength;
    if (softening_factor <= 0.0) return 0.0;
    return tensile_strength - kn / softening_factor * (max_elongation - peak_elongation);
  }

  [[nodiscard]] ContactForce evaluate(const ContactKinematics& k, double* history) const noexcept;

  /// Adds `force` (on the first body) to a bonded contact's stored load, its
  /// normal part with the peripheral elongation the law's stiffness gives it
  /// (σ = k_n e, so Δe = ΔN/(k_n A)): a state the bond could have reached by
  /// elastic deformation (seam balance, seam_balance.hpp).
  void add_bond_load(double* history, const ContactKinematics& k, const Vec3& force) const noexcept {
    const BondSection s = bond_section(k, radius_multiplier);
    BondLoad load = BondLoad::load(history + load_offset, k);
    const double normal = dot(force, k.normal);
    load.normal += normal;
    load.shear += force - normal * k.normal;
    load.store(history + load_offset);
    history[elongation_column] += normal / (deformability_bond_kn(k, emod) * s.area);
    history[max_elongation_column] = std::max(history[max_elongation_column], history[elongation_column]);
  }
};

static_assert(ContactLawKernel<SoftBondLaw>);

inline ContactForce SoftBondLaw::evaluate(const ContactKinematics& k, double* history) const noexcept {
  const BondSection s = bond_section(k, radius_multiplier);
  const double kn = deformability_bond_kn(k, emod);
  BondState state = bond_state(history);
  if (is_bonded(state)) {
    BondLoad load = BondLoad::load(history + load_offset, k);
    const BondIncrements d = bond_increments(k);
    const double bend_before = norm(load.bend);
    load.add_elastic(d, BondStiffness::of(s, kn, kn / kratio));
    const double elongation =
        history[elongation_column] + d.normal + moment_factor * s.radius * (norm(load.bend) - bend_before) / (kn * s.inertia);
    const double max_elongation = std::max(history[max_elongation_column], elongation);
    // Tension: elastic below the (softened) strength, capped on it above.
    const double trial = peak_stresses(load, s, moment_factor).tension;
    const double strength = softened_strength(kn, max_elongation);
    if (trial >= tensile_strength || max_elongation > tensile_strength / kn) {
      if (max_elongation >= breaking_elongation(kn) || strength <= cut_factor * tensile_strength) state = BondState::broken_tension;
      else state = BondState::damaged;
    }
    if (is_bonded(state) && trial > strength) {
      const double bending_stress = moment_factor * norm(load.bend) * s.radius / s.inertia;
      if (load.normal > 0.0) {
        const double scale = strength / trial;
        load.normal *= scale;
        load.bend *= scale;
      } else {  // compressive N keeps its value: only the bending part is above the cap
        load.bend *= (strength - load.normal / s.area) / bending_stress;
      }
    }
    if (is_bonded(state)) {
      const double sigma = load.normal / s.area;
      if (peak_stresses(load, s, moment_factor).shear >= shear_strength(sigma, cohesion, tan_friction_angle, tensile_strength))
        state = BondState::broken_shear;
    }
    set_bond_state(history, state);
    if (is_bonded(state)) {
      load.store(history + load_offset);
      history[elongation_column] = elongation;
      history[max_elongation_column] = max_elongation;
      return {load.force(k.normal), load.couple(k.normal)};
    }
    BondLoad::clear(history + load_offset);
    history[elongation_column] = history[max_elongation_column] = 0.0;
  }
  if (k.overlap <= 0.0) {
    separate(history);
    return {};
  }
  const double kc = kn * s.area;
  const LinearLaw unbonded{.kn = kc, .ks = kc / kratio, .friction = friction, .damping_ratio_normal = damping_ratio_normal,
                           .damping_ratio_shear = damping_ratio_shear};
  return {unbonded.evaluate(k, history + linear_offset).on_first, {}};
}

}  // namespace dfc::dem
