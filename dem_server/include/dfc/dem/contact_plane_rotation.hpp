#pragma once
// Stored in-plane vectors (shear forces, bending moments, shear or bending
// displacements) carried into the current contact plane, every step, before a
// law adds this step's increments (reference/dem-physics.md §2.3; PFC's
// convention: project, then restore the magnitude; LAMMPS gran/hooke/history
// projects without restoring it), or turned by the rotation of the contact
// frame itself when the law keeps the previous normal.
#include <cmath>
#include <cstddef>

#include "dfc/dem/vec3.hpp"

namespace dfc::dem {

[[nodiscard]] inline Vec3 load_vec3(const double* h) noexcept { return {h[0], h[1], h[2]}; }
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
/// between them (Rodrigues; reference/dem-physics.md §8 item 3: stored shear
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

/// Carries, in place, every in-plane vector of a contact's history into the
/// plane normal to `normal`: the 3 doubles at each offset of Law::in_plane_history
/// (contact_model.hpp RotatesInPlaneHistory). A law that stores the previous
/// step's normal (Law::previous_normal_offset, 3 doubles) turns them all with
/// one ContactFrameRotation and stores the new normal; any other projects and
/// rescales each (rotate_into_contact_plane).
template <class Law>
void rotate_in_plane_history(double* history, const Vec3& normal) noexcept {
  if constexpr (requires { Law::previous_normal_offset; }) {
    double* stored_normal = history + Law::previous_normal_offset;
    const ContactFrameRotation rotation = ContactFrameRotation::between(load_vec3(stored_normal), normal);
    for (const std::size_t offset : Law::in_plane_history) store_vec3(history + offset, rotation.apply(load_vec3(history + offset)));
    store_vec3(stored_normal, normal);
  } else {
    for (const std::size_t offset : Law::in_plane_history) store_vec3(history + offset, rotate_into_contact_plane(load_vec3(history + offset), normal));
  }
}

}  // namespace dfc::dem
