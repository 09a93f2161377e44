#pragma once
// Stored in-plane vectors (shear forces, bending moments, shear or bending
// displacements) carried into the current contact plane, every step, before a
// law adds this step's increments (reference/dem-physics.md §2.3; PFC's
// convention: project, then restore the magnitude; LAMMPS gran/hooke/history
// projects without restoring it).
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

/// Carries, in place, every in-plane vector of a contact's history into the
/// plane normal to `normal`: the 3 doubles at each offset of Law::in_plane_history
/// (contact_model.hpp RotatesInPlaneHistory).
template <class Law>
void rotate_in_plane_history(double* history, const Vec3& normal) noexcept {
  for (const std::size_t offset : Law::in_plane_history) store_vec3(history + offset, rotate_into_contact_plane(load_vec3(history + offset), normal));
}

}  // namespace dfc::dem
