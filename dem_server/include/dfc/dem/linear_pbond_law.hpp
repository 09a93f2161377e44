#pragma once
// `linear_pbond`: the linear parallel bond (Potyondy & Cundall 2004, IJRMMS
// 41:1329; Itasca PFC linearpbond; docs/theory/dem_contact_laws.md §2).
//
//   linear part (always, while the surfaces overlap): the `linear` law with
//     k_n = π E* R_min²/(R1+R2), k_s = k_n/κ*                    (§2.2)
//   bond (while bonded), disc of radius R̄ = λ̄ R_min:             (§2.1)
//     incremental N, F_s, M_t, M_b with k̄_n = Ē*/(R1+R2), k̄_s = k̄_n/κ̄*  (§2.3)
//     σ̄ = N/A + β̄|M_b|R̄/I >= σ̄_c  -> broken in tension       (§2.4–2.5)
//     τ̄ = |F_s|/A + β̄|M_t|R̄/J >= c̄ - σ tan φ̄ -> broken in shear
//   A broken bond is removed with its force, moment and stiffness: the
//   contact is the linear frictional one alone. The tension test comes
//   first (the order is [unconfirmed] in the reference; with brittle failure
//   it only decides the label when both limits are passed in one step).
//
// History (15): state, BondLoad (8), linear shear force (3), the previous
// step's normal (3). The stored shear force and bending moment of the bond and
// the linear shear force turn with the contact frame from the previous normal
// to the current one (contact_plane_rotation.hpp ContactFrameRotation; dem_contact_laws.md §4).
#include <array>
#include <cmath>
#include <span>
#include <string_view>
#include <vector>

#include "dfc/dem/bond_state.hpp"
#include "dfc/dem/linear_law.hpp"
#include "dfc/dem/parallel_bond_forces.hpp"

namespace dfc::dem {

struct LinearPbondLaw {
  static constexpr std::string_view keyword = "linear_pbond";
  static constexpr std::size_t load_offset = 1;
  static constexpr std::size_t linear_offset = load_offset + BondLoad::history_size;
  static constexpr std::size_t previous_normal_offset = linear_offset + LinearLaw::history_size;
  static constexpr std::size_t history_size = previous_normal_offset + 3;
  static constexpr bool has_couple = true;
  static constexpr bool acts_across_gap = true;  // a bond holds across a gap
  static constexpr bool bonded = true;

  double emod = 0.0;                  ///< Pa, E* of the linear part
  double kratio = 1.0;                ///< -, κ* = k_n / k_s
  double friction = 0.5;              ///< -
  double damping_ratio_normal = 0.0;  ///< - (linear part)
  double bond_emod = 0.0;             ///< Pa, Ē*
  double bond_kratio = 1.0;           ///< -, κ̄*
  double radius_multiplier = 1.0;     ///< -, λ̄
  double moment_factor = 1.0;         ///< -, β̄
  double tensile_strength = 0.0;      ///< Pa, σ̄_c
  double cohesion = 0.0;              ///< Pa, c̄
  double tan_friction_angle = 0.0;    ///< -, tan φ̄
  double bond_gap = 0.0;              ///< m, pairs with a surface gap <= this are bonded at start
  double damping_ratio_shear = 0.0;   ///< - (linear part)

  [[nodiscard]] static std::vector<HistoryColumn> history_columns();
  [[nodiscard]] static LinearPbondLaw from_parameters(const LawParameters& values);

  [[nodiscard]] StiffnessBound stiffness_bound(double radius_max) const noexcept {
    const double kn = deformability_kn_bound(emod, radius_max);
    const double kbn = deformability_kn_bound(bond_emod, radius_max) * radius_multiplier * radius_multiplier;
    return {kn + kbn, kn / kratio + kbn / bond_kratio};
  }

  /// SkipsIdleGaps: without an intact bond a gap carries nothing (evaluate
  /// returns zero and calls separate).
  [[nodiscard]] static bool idle_across_gap(const double* history) noexcept { return bond_state(history) != BondState::intact; }

  /// A contact that carries nothing: no linear part, and no previous normal
  /// (no stored vector left to turn).
  void separate(double* history) const noexcept {
    for (std::size_t c = linear_offset; c < history_size; ++c) history[c] = 0.0;
  }

  /// Pair constants (contact_model.hpp HasPairConstants), in this order.
  enum Constant : std::size_t {
    kn_linear,
    ks_linear,
    dashpot_linear,  // LinearLaw's pair constants
    bond_stiffness = dashpot_linear + LinearLaw::constants_size,  // BondStiffness, 4 doubles
    moment_per_radius = bond_stiffness + 4,
    tension_limit,   // σ̄_c A
    cohesion_force,  // c̄ A
    constants_size_
  };
  static constexpr std::size_t constants_size = constants_size_;
  void pair_constants(const ContactKinematics& k, double* c) const noexcept {
    c[kn_linear] = deformability_kn(k, emod);
    c[ks_linear] = c[kn_linear] / kratio;
    linear_part(c).pair_constants(k, c + dashpot_linear);
    const double kn_bond = deformability_bond_kn(k, bond_emod);
    const BondSection s = bond_section(k, radius_multiplier);
    const BondStiffness stiffness = BondStiffness::of(s, kn_bond, kn_bond / bond_kratio);
    c[bond_stiffness] = stiffness.normal;
    c[bond_stiffness + 1] = stiffness.shear;
    c[bond_stiffness + 2] = stiffness.twist;
    c[bond_stiffness + 3] = stiffness.bend;
    c[moment_per_radius] = moment_factor / s.radius;
    c[tension_limit] = tensile_strength * s.area;
    c[cohesion_force] = cohesion * s.area;
  }

  [[nodiscard]] ContactForce evaluate(const ContactKinematics& k, double* history) const noexcept {
    double c[constants_size];
    pair_constants(k, c);
    return evaluate(k, c, history);
  }

  [[nodiscard]] ContactForce evaluate(const ContactKinematics& k, const double* c, double* history) const noexcept {
    rotate_in_plane_history<LinearPbondLaw>(history, k);
    return evaluate_in_plane(k, c, history);
  }

  /// The bond's shear force and bending moment and the linear part's shear
  /// force turn with the contact plane (RotatesInPlaneHistory), all by one
  /// rotation of the contact frame from the normal stored here.
  static constexpr std::array<std::size_t, 3> in_plane_history{load_offset + BondLoad::shear_offset, load_offset + BondLoad::bend_offset,
                                                               linear_offset};

  /// evaluate() for a history already carried into k's contact plane.
  // always_inline: at this size GCC kept it out of line, a call per contact
  // with the kinematics passed through memory (measured: +14 % bonded throughput inlined).
  [[nodiscard]] [[gnu::always_inline]] ContactForce evaluate_in_plane(const ContactKinematics& k, const double* c, double* history) const noexcept {
    ContactForce out{};
    BondState state = bond_state(history);
    if (state == BondState::intact) {
      BondLoad load = BondLoad::load_in_current_plane(history + load_offset);
      const BondStiffness stiffness{c[bond_stiffness], c[bond_stiffness + 1], c[bond_stiffness + 2], c[bond_stiffness + 3]};
      load.add_elastic(bond_increments(k), stiffness);
      if (!surely_below_limits(load, c[moment_per_radius], c[tension_limit], c[cohesion_force], tan_friction_angle)) {
        const BondSection s = bond_section(k, radius_multiplier);
        const PeakStresses peak = peak_stresses(load, s, moment_factor);
        const double strength = shear_strength(load.normal / s.area, cohesion, tan_friction_angle, tensile_strength);
        if (peak.tension >= tensile_strength) state = BondState::broken_tension;
        else if (peak.shear >= strength) state = BondState::broken_shear;
      }
      if (state == BondState::intact) {
        load.store(history + load_offset);
        out = {load.force(k.normal), load.couple(k.normal)};
      } else {
        set_bond_state(history, state);
        BondLoad::clear(history + load_offset);
      }
    }
    double* shear = history + linear_offset;
    if (k.overlap <= 0.0) {
      if (state == BondState::intact) {
        // Surfaces apart, bond holding: only the linear part lets go; the bond's vectors keep turning.
        for (std::size_t column = 0; column < LinearLaw::history_size; ++column) shear[column] = 0.0;
      } else {
        separate(history);
      }
      return out;
    }
    out.on_first += linear_part(c).evaluate_in_plane(k, c + dashpot_linear, shear).on_first;
    return out;
  }

 private:
  /// The linear frictional contact of this pair (its stiffnesses are pair constants).
  [[nodiscard]] LinearLaw linear_part(const double* c) const noexcept {
    return {.kn = c[kn_linear],
            .ks = c[ks_linear],
            .friction = friction,
            .damping_ratio_normal = damping_ratio_normal,
            .damping_ratio_shear = damping_ratio_shear};
  }
};

static_assert(RotatesInPlaneHistory<LinearPbondLaw> && SkipsIdleGaps<LinearPbondLaw>);

}  // namespace dfc::dem
