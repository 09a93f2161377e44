#pragma once
// What every contact law sees and returns, and what it must declare.
//
// A law is a small value type (its parameters) with an inline `evaluate`
// called once per contact by a kernel templated on the law
// (contact_kernels.hpp): the law is chosen once per step by std::visit, never
// by a virtual call per contact. A new law (linear_pbond, soft_bond,
// damage_bond) is a new type satisfying `ContactLawKernel` plus one registry
// entry (contact_law_registry.cpp); the loops do not change.
#include <concepts>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "dfc/common/config_reader.hpp"
#include "dfc/dem/vec3.hpp"

namespace dfc::dem {

/// State of one contact between a "first" body (always a particle) and a
/// "second" body (a particle or a wall facet), evaluated at the current positions.
struct ContactKinematics {
  Vec3 normal;                     ///< unit vector from the first body's centre towards the second body
  double overlap = 0.0;            ///< m; r1 + r2 - d (wall: r1 - d); > 0 in contact, <= 0 a gap
  Vec3 relative_velocity;          ///< m/s, velocity of the second body's material point at the contact minus the first's
  Vec3 relative_angular_velocity;  ///< rad/s, omega_2 - omega_1 (bonded laws: bending and twisting increments)
  /// rad/s, (omega_1 + omega_2)/2 · normal: the pair's common spin about the
  /// normal, which turns the contact plane about itself (the "twirl" of the
  /// stored in-plane vectors, contact_plane_rotation.hpp ContactTwirl); a wall
  /// does not spin, so at a wall contact it is omega_1 · normal / 2.
  double mean_spin_about_normal = 0.0;
  double effective_mass = 0.0;     ///< kg, m1 m2 / (m1 + m2); a wall counts as infinitely heavy (= m1)
  double radius_first = 0.0;       ///< m
  double radius_second = 0.0;      ///< m; 0 for a wall facet (PFC: a ball–facet contact uses the ball radius only)
  double dt = 0.0;                 ///< s, the time step (incremental laws)
};

/// ContactKinematics::mean_spin_about_normal of bodies spinning at w1 and w2.
[[nodiscard]] inline double mean_spin_about_normal(const Vec3& w1, const Vec3& w2, const Vec3& normal) noexcept {
  return 0.5 * dot(w1 + w2, normal);
}

/// What a law returns: the force on the first body, acting at the contact
/// point, and an optional pure couple. The second body receives the opposite.
struct ContactForce {
  Vec3 on_first;         ///< N
  Vec3 couple_on_first;  ///< N m (laws with has_couple only)
};

/// Largest translational stiffnesses a law can present, for the critical time step.
struct StiffnessBound {
  double normal = 0.0;  ///< N/m
  double shear = 0.0;   ///< N/m
};

/// A law's parameter values, in the order of its declaration
/// (dfc/common/sections/dem_contact_laws.hpp), read by key: laws are built
/// from named values, never from positions.
class LawParameters {
 public:
  LawParameters(std::span<const ParameterDeclaration> declared, std::span<const double> values);
  /// The value of `key`; std::logic_error if the law's declaration lacks it.
  [[nodiscard]] double operator[](std::string_view key) const;

 private:
  std::span<const ParameterDeclaration> declared_;
  std::span<const double> values_;
};

/// One column of per-contact history (e.g. the x component of the shear force).
struct HistoryColumn {
  std::string name;
  std::string unit;
};

/// The compile-time contract of a contact law kernel.
template <class Law>
concept ContactLawKernel = requires(const Law law, const ContactKinematics& k, double* history) {
  { Law::history_size } -> std::convertible_to<std::size_t>;  // doubles of history per contact
  { Law::has_couple } -> std::convertible_to<bool>;           // returns a pure couple as well as a force
  { Law::acts_across_gap } -> std::convertible_to<bool>;      // false: a contact with overlap <= 0 carries nothing
  { Law::bonded } -> std::convertible_to<bool>;               // keeps a BondState in history column 0 (bond_state.hpp)
  { law.evaluate(k, history) } -> std::same_as<ContactForce>;
  { law.separate(history) } -> std::same_as<void>;             // the contact opened: reset its history
  { law.stiffness_bound(1.0) } -> std::same_as<StiffnessBound>;  // for radii up to the argument (m)
};

/// Optional part of a law: per-contact constants that depend only on the two
/// bodies (radii, effective mass) and the law's parameters, e.g. stiffnesses of
/// the deformability method or a dashpot coefficient. The pair loop computes
/// them once per list rebuild instead of every step (divisions and square
/// roots are its slowest operations). `evaluate(k, constants, history)` must
/// give bit for bit what `evaluate(k, history)` gives, which computes them on
/// the spot (wall contacts and tests use that one).
template <class Law>
concept HasPairConstants = ContactLawKernel<Law> && requires(const Law law, const ContactKinematics& k, const double* constants, double* out,
                                                             double* history) {
  { Law::constants_size } -> std::convertible_to<std::size_t>;
  { law.pair_constants(k, out) } -> std::same_as<void>;  // from k's radii and effective mass only
  { law.evaluate(k, constants, history) } -> std::same_as<ContactForce>;
};

/// Optional part of a law whose history holds in-plane vectors (shear forces,
/// bending moments) that turn with the contact plane every step:
/// Law::in_plane_history lists their offsets in the history row (3 doubles
/// each; contact_plane_rotation.hpp rotate_in_plane_history), and
/// `evaluate_in_plane(k, constants, history)` is `evaluate(k, constants,
/// history)` for a history already carried into k's plane. The pair loop
/// rotates a batch of contacts before it evaluates them: each rotation's
/// division (and square roots) are then independent of the next contact's,
/// and the processor overlaps them instead of waiting on each (the operations
/// are the same, so are the results). A law may also declare
/// Law::previous_normal_offset (3 history doubles it keeps for this): its
/// vectors then turn with the contact frame from that normal, all by one
/// rotation (ContactFrameRotation), and the new normal is stored.
template <class Law>
concept RotatesInPlaneHistory = HasPairConstants<Law> && requires(const Law law, const ContactKinematics& k, const double* constants, double* history) {
  { Law::in_plane_history.size() } -> std::convertible_to<std::size_t>;
  { law.evaluate_in_plane(k, constants, history) } -> std::same_as<ContactForce>;
};

/// Optional part of a law whose history has columns most contacts hold at
/// zero for a whole run (damage_bond's plastic parts, zero until a bond
/// yields): the last Law::cold_history_size of its history_size columns live
/// in a second row (PairContacts::cold_history), which the pair loop neither
/// prefetches nor passes through the stage that turns in-plane vectors; the
/// law reads and writes it where it needs it. A whole row (tests, the history
/// archive, snapshots, the single-row evaluate) is the hot columns followed by
/// the cold ones. Why: the paper model streams its pair rows from memory
/// every step, and 7 of damage_bond's 23 doubles are zeros there.
/// `evaluate_in_plane(k, constants, hot, cold)` is RotatesInPlaneHistory's
/// evaluate_in_plane on the two parts of the row (Law::in_plane_history
/// offsets are in the hot part).
template <class Law>
concept SplitsHistory = RotatesInPlaneHistory<Law> && requires(const Law law, const ContactKinematics& k, const double* constants, double* hot,
                                                               double* cold) {
  { Law::cold_history_size } -> std::convertible_to<std::size_t>;
  { law.evaluate_in_plane(k, constants, hot, cold) } -> std::same_as<ContactForce>;
};

/// Law::cold_history_size, or 0 for a law whose history is one row.
template <class Law>
[[nodiscard]] constexpr std::size_t cold_history_size_of() noexcept {
  if constexpr (SplitsHistory<Law>) return Law::cold_history_size;
  else return 0;
}

/// Optional part of a law that acts across a gap (a bond): true when this
/// contact's history says it carries nothing while the surfaces are apart
/// (e.g. no intact bond), where evaluate would return zero and only call
/// separate; the pair loop then skips the contact's kinematics.
template <class Law>
concept SkipsIdleGaps = ContactLawKernel<Law> && Law::acts_across_gap && requires(const double* history) {
  { Law::idle_across_gap(history) } -> std::same_as<bool>;
};

}  // namespace dfc::dem
