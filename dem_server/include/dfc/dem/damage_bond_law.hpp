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
// History (23): state, D, u_n, u_s (3), θ_t, θ_b (3), ū_n^p, ū_s^p, θ̄_b^p,
// linear shear force (3) in the row every step reads (16 doubles, two cache
// lines), then the plastic parts u_n^p, u_s^p (3), θ_b^p (3) in a second row
// (contact_model.hpp SplitsHistory) read and written only once the bond has
// yielded: before that they are zero, and so are the accumulated measures,
// which tell (plastic_in_use). The paper model's pairs at rest are mostly
// intact bonds: their 56 bytes of zeros per step no longer come from memory
// (docs/dem_benchmarks.md).
#include <array>
#include <cmath>
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
  /// Columns of the row every step reads (and of a whole row, hot then cold).
  enum Column : std::size_t {
    state = 0, damage = 1, opening = 2, slip = 3, twist = 6, bend = 7,
    accumulated_opening = 10, accumulated_slip = 11, accumulated_bend = 12, linear_shear = 13,
  };
  /// Columns of the second row (the plastic parts), from its start.
  enum PlasticColumn : std::size_t { plastic_opening = 0, plastic_slip = 1, plastic_bend = 4 };
  static constexpr std::size_t history_size = 23;
  static constexpr std::size_t cold_history_size = 7;  ///< the plastic parts: columns 16-22 of a whole row
  static constexpr std::size_t hot_history_size = history_size - cold_history_size;
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

  /// Sets the linear contact's shear force to +0; one already +0 is not
  /// stored again (an intact bond separates every step: its row's last
  /// cache line then stays clean).
  void separate(double* history) const noexcept {
    if (!is_positive_zero_vec3(history + linear_shear)) store_vec3(history + linear_shear, {});
  }

  /// SkipsIdleGaps: without a bond (never bonded, or broken) a gap carries
  /// nothing: evaluate returns zero and calls separate.
  [[nodiscard]] static bool idle_across_gap(const double* history) noexcept { return !is_bonded(bond_state(history)); }

  /// Pair constants (contact_model.hpp HasPairConstants): the bond's
  /// stiffnesses, two divisions per bond that depend on the radii alone, so
  /// the pair loop computes them at a list rebuild instead of every step (the
  /// same expressions, so the same bits). The section (products only) and the
  /// linear contact (it acts on damaged or broken bonds in contact, a few) are
  /// computed where used: 16 bytes per pair instead of 80.
  enum Constant : std::size_t {
    bond_kn,  // k̄_n = Ē*/(R1+R2)
    bond_ks,  // k̄_s = k̄_n/κ̄*
    constants_size_
  };
  static constexpr std::size_t constants_size = constants_size_;
  void pair_constants(const ContactKinematics& k, double* c) const noexcept {
    c[bond_kn] = deformability_bond_kn(k, bond_emod);
    c[bond_ks] = c[bond_kn] / bond_kratio;
  }

  /// The bond's displacements (m, rad) during one update: the elastic parts
  /// e = u - u^p and the plastic parts u^p, in the current contact plane.
  struct Strain {
    double opening = 0.0;
    Vec3 slip;
    Vec3 bend;
    double plastic_opening = 0.0;
    Vec3 plastic_slip;
    Vec3 plastic_bend;
  };

  /// D of the corrected Eq. 2 from the accumulated plastic measures.
  [[nodiscard]] double damage_from(double opening_p, double slip_p, double bend_p) const noexcept;

  /// True once the bond has yielded: its plastic parts (the cold row) may be
  /// non-zero. Before, they are +0 (a new row, a broken bond's cleared ones),
  /// as are the accumulated measures: any plastic increment adds its size to
  /// them (yield), so a non-zero plastic part comes with a positive measure.
  [[nodiscard]] static bool plastic_in_use(const double* h) noexcept {
    return h[accumulated_opening] != 0.0 || h[accumulated_slip] != 0.0 || h[accumulated_bend] != 0.0;
  }

  /// Elastic trial, return to the envelope, damage and breakage of a bonded
  /// contact whose stored vectors are already in k's contact plane; returns
  /// the bond's force and couple on the first body. h is the row every step
  /// reads, p the plastic parts (read and written only where plastic_in_use,
  /// before or after the return).
  [[nodiscard]] [[gnu::always_inline]] ContactForce update_bond(const ContactKinematics& k, const double* c, double* h, double* p) const noexcept {
    // 1. Total displacements and the plastic parts (+0 before the first yield:
    // u - (+0) is u to the bit, so the elastic parts are those of the stored zeros).
    const BondIncrements d = bond_increments(k);
    const double u_n = h[opening] + d.normal;
    const Vec3 u_s = load_vec3(h + slip) + d.shear;
    const double theta_t = h[twist] + d.twist;
    const Vec3 theta_b = load_vec3(h + bend) + d.bend;
    const bool yielded = plastic_in_use(h);
    const double u_np = yielded ? p[plastic_opening] : 0.0;
    const Vec3 u_sp = yielded ? load_vec3(p + plastic_slip) : Vec3{}, theta_bp = yielded ? load_vec3(p + plastic_bend) : Vec3{};
    Strain e{.opening = u_n - u_np, .slip = u_s - u_sp, .bend = theta_b - theta_bp, .plastic_opening = u_np, .plastic_slip = u_sp, .plastic_bend = theta_bp};

    // 2.-4. Elastic trial, return to the envelope and damage, unless the trial
    // is surely inside the envelope (then the full test says so too).
    double damage_value = h[damage];
    if (!surely_elastic(e, c, k)) {
      damage_value = yield(e, c, k, h);
      // Otherwise the plastic parts are the stored ones (already in this
      // plane): not stored again, which would only dirty their cache line;
      // nor where the return left them at +0 (no yield yet).
      if (plastic_in_use(h)) {
        p[plastic_opening] = e.plastic_opening;
        store_vec3(p + plastic_slip, e.plastic_slip);
        store_vec3(p + plastic_bend, e.plastic_bend);
      }
    }

    // 5. Breakage (§3.6): the bond and its displacements are removed.
    if (damage_value > breakage_damage) {
      break_bond(e.opening, h, p);
      return {};
    }
    h[damage] = damage_value;
    set_bond_state(h, damage_value > 0.0 ? BondState::damaged : BondState::intact);
    h[opening] = u_n;
    store_vec3(h + slip, u_s);
    h[twist] = theta_t;
    store_vec3(h + bend, theta_b);

    // 6. Forces (Eq. 1) on the first body: tension pulls it along +n.
    const BondSection s = bond_section(k, radius_multiplier);
    const double intact = 1.0 - damage_value;
    const double kn = c[bond_kn], ks = c[bond_ks];
    const double normal_force = intact * kn * s.area * e.opening;
    const Vec3 shear_force = (intact * ks * s.area) * e.slip;
    const Vec3 couple = (intact * kn * s.inertia) * e.bend + (intact * ks * s.polar * theta_t) * k.normal;
    return {shear_force + normal_force * k.normal, couple};
  }

  /// Adds `force` (on the first body) to a bonded contact's load through its
  /// elastic displacements: Δu_n = ΔN/((1-D) k̄_n A), Δu_s = ΔV/((1-D) k̄_s A)
  /// (Eq. 1), so the bond holds a state it could have reached elastically
  /// (seam balance, seam_balance.hpp). The envelope is checked at the next
  /// evaluation. Reads and writes the row every step reads only.
  void add_bond_load(double* history, const ContactKinematics& k, const Vec3& force) const noexcept {
    const double area = bond_section(k, radius_multiplier).area;
    const double kn = deformability_bond_kn(k, bond_emod), ks = kn / bond_kratio, intact = 1.0 - history[damage];
    const double normal = dot(force, k.normal);
    history[opening] += normal / (intact * kn * area);
    store_vec3(history + slip, load_in_plane(history + slip, k.normal, ContactTwirl::of(k)) + (1.0 / (intact * ks * area)) * (force - normal * k.normal));
  }

  /// A whole row (hot then cold columns, contiguous: tests, the history archive).
  [[nodiscard]] ContactForce evaluate(const ContactKinematics& k, double* history) const noexcept {
    double c[constants_size];
    pair_constants(k, c);
    return evaluate(k, c, history);
  }

  [[nodiscard]] ContactForce evaluate(const ContactKinematics& k, const double* c, double* history) const noexcept {
    rotate_in_plane_history<DamageBondLaw>(history, k);
    return evaluate_in_plane(k, c, history, history + hot_history_size);
  }

  /// The elastic slip and bending and the linear contact's shear force turn
  /// with the contact plane (RotatesInPlaneHistory), bonded or not: a vector
  /// a law does not use at that step is +0 (a new row, a broken bond's
  /// cleared columns, a linear shear force that separate() reset), and the
  /// turn keeps +0 as +0 exactly (rotate_into_contact_plane returns a zero
  /// vector as it is; the twirl adds cos·(+0) = +0 and sin·(±0), and +0 + ±0
  /// = +0, for cos > 0, i.e. a turn below 90° per step), so the results are
  /// those of turning them only where used. The plastic parts (cold_in_plane_history)
  /// turn the same way, in evaluate_in_plane, once the bond has yielded; before, they are +0.
  static constexpr std::array<std::size_t, 3> in_plane_history{slip, bend, linear_shear};
  static constexpr std::array<std::size_t, 2> cold_in_plane_history{plastic_slip, plastic_bend};

  /// The same on a whole row (hot then cold columns, contiguous).
  [[nodiscard]] ContactForce evaluate_in_plane(const ContactKinematics& k, const double* c, double* history) const noexcept {
    return evaluate_in_plane(k, c, history, history + hot_history_size);
  }

  /// evaluate() for a row whose in_plane_history vectors are already carried
  /// into k's contact plane; p is the cold row (the plastic parts), turned here where in use.
  [[nodiscard]] [[gnu::always_inline]] ContactForce evaluate_in_plane(const ContactKinematics& k, const double* c, double* history, double* p) const noexcept {
    ContactForce out{};
    if (is_bonded(bond_state(history))) {
      if (plastic_in_use(history)) rotate_stored_vectors(p, cold_in_plane_history, k);
      out = update_bond(k, c, history, p);
    }
    // The linear contact acts once the bond is damaged or gone (§3.6).
    if (bond_state(history) == BondState::intact || k.overlap <= 0.0) {
      separate(history);
      return out;
    }
    const double kn = deformability_kn(k, emod);
    const LinearLaw linear{.kn = kn, .ks = kn / kratio, .friction = friction, .damping_ratio_normal = damping_ratio_normal,
                           .damping_ratio_shear = damping_ratio_shear};
    double linear_constants[LinearLaw::constants_size];
    linear.pair_constants(k, linear_constants);
    out.on_first += linear.evaluate_in_plane(k, linear_constants, history + linear_shear).on_first;
    return out;
  }

  /// True when the elastic trial lies well inside the envelope, tested
  /// without its divisions and square roots: |N|/N̄ <= 1/2, |V|/V̄ <= 1/2 and
  /// |M̆|/M̃ <= 1/4 (in squares) give n² + v⁴/(1-n²) + m <= 0.584, far inside
  /// outside_damage_envelope's first test (<= 1 - 1e-12) whatever the
  /// round-off, so where this holds that test finds the trial inside as well.
  /// False for NaN (then the full test decides, as before).
  [[nodiscard]] bool surely_elastic(const Strain& e, const double* c, const ContactKinematics& k) const noexcept {
    const double kn = c[bond_kn], ks = c[bond_ks];
    const double sigma_0 = e.opening >= 0.0 ? tensile_strength : compressive_strength;
    const double bend_stiffness = kn * (radius_multiplier * contact_min_radius(k));
    return std::abs(kn * e.opening) <= 0.5 * sigma_0 && ks * ks * norm2(e.slip) <= 0.25 * cohesion * cohesion &&
           bend_stiffness * bend_stiffness * norm2(e.bend) <= 0.0625 * tensile_strength * tensile_strength;
  }

 private:
  /// Steps 2-4 of update_bond: the elastic trial in normalised coordinates
  /// (the (1-D) factors cancel), the closest-point return (energy norm) with
  /// the plastic increments it implies, and the damage (corrected Eq. 2,
  /// never lowered). Updates e and the accumulated measures in h; returns D.
  [[nodiscard]] double yield(Strain& e, const double* c, const ContactKinematics& k, double* h) const noexcept;

  /// Step 5 of update_bond: clears the bond (both rows) and labels its failure.
  void break_bond(double elastic_opening, double* h, double* p) const noexcept;
};

static_assert(SplitsHistory<DamageBondLaw> && SkipsIdleGaps<DamageBondLaw>);

}  // namespace dfc::dem
