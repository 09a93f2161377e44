#pragma once
// Stored in-plane vectors (shear forces, bending moments, shear or bending
// displacements) carried into the current contact plane, every step, before a
// law adds this step's increments (docs/theory/dem_contact_laws.md §2.3 and §4:
// they turn with the contact frame). The frame turns in two parts, as in
// PFC3D's contact update:
//   tilt:  the plane follows its normal from the previous step's to the
//          current one: projected, then the magnitude restored (PFC's
//          convention; LAMMPS gran/hooke/history projects without restoring
//          it), or turned by the smallest rotation between the two normals
//          when the law keeps the previous normal (ContactFrameRotation);
//   twirl: the plane turns about its own normal with the pair's common spin,
//          (omega_1 + omega_2)/2 · n dt (ContactTwirl). Without it a pair that
//          spins rigidly about its line of centres leaves its stored shear
//          force fixed in space while the bodies turn under it: the contact
//          force is then not objective and the stress from the contacts not a
//          tensor (M. R. Kuhn et al. 2020, "Linear-frictional contact model
//          for 3D discrete element simulations of granular systems", its
//          "twirling" correction; Itasca PFC3D 3.x Theory and Background, the
//          second rotation of the shear force, by the mean spin of the two
//          bodies about the normal).
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "dfc/dem/contact_model.hpp"
#include "dfc/dem/vec3.hpp"

namespace dfc::dem {

[[nodiscard]] inline Vec3 load_vec3(const double* h) noexcept { return {h[0], h[1], h[2]}; }
/// True when the 3 doubles at h are +0, every bit zero (a -0 is not).
[[nodiscard]] inline bool is_positive_zero_vec3(const double* h) noexcept {
  return (std::bit_cast<std::uint64_t>(h[0]) | std::bit_cast<std::uint64_t>(h[1]) | std::bit_cast<std::uint64_t>(h[2])) == 0;
}
inline void store_vec3(double* h, const Vec3& v) noexcept {
  h[0] = v.x;
  h[1] = v.y;
  h[2] = v.z;
}

/// Projects a stored in-plane vector onto the plane normal to `normal` and
/// restores its magnitude: the first-order rotation with the contact plane.
[[nodiscard]] inline Vec3 rotate_into_contact_plane(const Vec3& v, const Vec3& normal) noexcept {
  const double before2 = norm2(v);
  if (before2 == 0.0) return v;
  const Vec3 projected = v - dot(v, normal) * normal;
  const double after2 = norm2(projected);
  if (after2 == 0.0) return projected;
  return std::sqrt(before2 / after2) * projected;
}

/// The rotation that turns the contact plane from `previous` normal to
/// `normal` about their common perpendicular n0 × n1, the smallest rotation
/// between them (Rodrigues; docs/theory/dem_contact_laws.md §4: stored shear
/// forces and moments turn with the contact frame). For v in the old plane
/// (v·n0 = 0) Rodrigues' formula reduces to
///   R v = v − (v·n1) (n0 + n1) / (1 + n0·n1),
/// which keeps |v| exactly and puts R v in the new plane; one division serves
/// every vector of the contact and there is no square root (measured on the
/// peer benchmark: −8.5 % bonded time against project-and-rescale per vector).
struct ContactFrameRotation {
  Vec3 axis_sum;              ///< n0 + n1
  double inverse_one_plus_cos = 0.0;  ///< 1 / (1 + n0·n1)
  Vec3 normal;                ///< n1

  /// A contact seen for the first time stores no previous normal (zero):
  /// then inverse_one_plus_cos = 1 and R v is the plain projection onto the new
  /// plane, which is exact for the only vectors such a contact has (zero).
  /// Opposite normals (1 + n0·n1 ≈ 0) cannot follow each other within a
  /// step (1 + n0·n1 < 1e-12 is n1 within 1.4e-6 rad of −n0); the
  /// projection is used there too rather than dividing by about zero.
  [[nodiscard]] static ContactFrameRotation between(const Vec3& previous, const Vec3& normal) noexcept {
    const double one_plus_cos = 1.0 + dot(previous, normal);
    if (!(one_plus_cos > 1e-12)) return {normal, 1.0, normal};
    return {previous + normal, 1.0 / one_plus_cos, normal};
  }
  [[nodiscard]] Vec3 apply(const Vec3& v) const noexcept { return v - (dot(v, normal) * inverse_one_plus_cos) * axis_sum; }
};

/// The turn of the contact plane about its own normal during one step, by
/// theta = mean_spin_about_normal * dt (see the top of this file). Applied as
/// the exact rotation by 2 atan(theta/2) (Cayley form: cos = (1 - t²)/(1 + t²),
/// sin = 2t/(1 + t²), t = theta/2): it keeps |v| to round-off with one
/// division and no trigonometric call, and differs from theta by theta³/12,
/// far below the O(theta²) error of the step's first-order kinematics. With
/// no spin it is the identity: cos = 1 and sin = 0, so v comes back unchanged
/// (a zero component may change sign).
struct ContactTwirl {
  double cos_angle = 1.0;
  double sin_angle = 0.0;

  [[nodiscard]] static ContactTwirl of(const ContactKinematics& k) noexcept {
    const double t = 0.5 * k.mean_spin_about_normal * k.dt;
    const double t2 = t * t;
    const double inverse = 1.0 / (1.0 + t2);
    return {(1.0 - t2) * inverse, 2.0 * t * inverse};
  }
  /// v (in the plane normal to `normal`) turned about `normal`.
  [[nodiscard]] Vec3 apply(const Vec3& v, const Vec3& normal) const noexcept { return cos_angle * v + sin_angle * cross(normal, v); }
};

/// The whole turn of a stored in-plane vector during a step for a law that
/// keeps no previous normal: tilted by projection with its magnitude restored
/// (rotate_into_contact_plane), then twirled. The twirl is formed once per
/// contact (ContactTwirl::of) and passed to each of its vectors.
// A free function on purpose: an aggregate holding a copy of the normal with
// the twirl, built per contact, was kept on the stack by GCC 12 and read back
// from it for every vector (perf: those loads were the hottest instructions):
// +45 % time of the whole unbonded benchmark (docs/dem_benchmarks.md, "What the code does for speed").
[[nodiscard]] inline Vec3 turn_with_contact_plane(const Vec3& v, const Vec3& normal, const ContactTwirl& twirl) noexcept {
  return twirl.apply(rotate_into_contact_plane(v, normal), normal);
}

/// Carries, in place, every in-plane vector of a contact's history into k's
/// contact plane: the 3 doubles at each offset of Law::in_plane_history
/// (contact_model.hpp RotatesInPlaneHistory). A law that stores the previous
/// step's normal (Law::previous_normal_offset, 3 doubles) tilts them all with
/// one ContactFrameRotation and stores the new normal; any other projects and
/// rescales each (rotate_into_contact_plane). Both then twirl them (ContactTwirl).
/// The vectors at `offsets` of `row` turned into k's contact plane by
/// projection and twirl (the rule of a law without a previous normal).
// A +0 vector turns into +0 exactly (rotate_into_contact_plane returns it as
// it is; the twirl gives cos·(+0) + sin·(±0) = +0 for cos > 0, a turn below
// 90° in a step), so it is left as it is: the same bits without the
// arithmetic, and without the store that would dirty its cache line (most
// rows of a bonded model hold such vectors: the contact force of an intact bond).
template <std::size_t N>
[[gnu::always_inline]] inline void rotate_stored_vectors(double* row, const std::array<std::size_t, N>& offsets, const ContactKinematics& k) noexcept {
  const ContactTwirl twirl = ContactTwirl::of(k);
  const bool keep_zeros = twirl.cos_angle > 0.0;
  for (const std::size_t offset : offsets) {
    if (keep_zeros && is_positive_zero_vec3(row + offset)) continue;
    store_vec3(row + offset, turn_with_contact_plane(load_vec3(row + offset), k.normal, twirl));
  }
}

template <class Law>
[[gnu::always_inline]] inline void rotate_in_plane_history(double* history, const ContactKinematics& k) noexcept {
  if constexpr (requires { Law::previous_normal_offset; }) {
    const ContactTwirl twirl = ContactTwirl::of(k);
    double* stored_normal = history + Law::previous_normal_offset;
    const ContactFrameRotation tilt = ContactFrameRotation::between(load_vec3(stored_normal), k.normal);
    for (const std::size_t offset : Law::in_plane_history)
      store_vec3(history + offset, twirl.apply(tilt.apply(load_vec3(history + offset)), k.normal));
    store_vec3(stored_normal, k.normal);
  } else {
    rotate_stored_vectors(history, Law::in_plane_history, k);
  }
}

}  // namespace dfc::dem
