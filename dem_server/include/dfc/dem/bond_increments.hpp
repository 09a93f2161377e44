#pragma once
// Relative motion of the two bodies across a bond during one step, split in
// the contact frame (docs/theory/dem_contact_laws.md §2.3, §4). Stored
// in-plane vectors turn with the contact plane (contact_plane_rotation.hpp).
//
// Sign convention of every bonded law (docs/theory/README.md, "Sign conventions"):
// opening and the normal bond force N are positive in TENSION (unlike the
// compression-positive linear law, whose no-tension spring it reuses as is).
// Stored shear forces and moments are those acting on the first body.
#include "dfc/dem/contact_model.hpp"
#include "dfc/dem/contact_plane_rotation.hpp"

namespace dfc::dem {

struct BondIncrements {
  double normal = 0.0;  ///< m, Δδ_n = v_n dt, > 0 opening
  Vec3 shear;           ///< m, Δδ_s = v_t dt (second body relative to the first, in the contact plane)
  double twist = 0.0;   ///< rad, Δθ_t = (ω2 - ω1)·n dt
  Vec3 bend;            ///< rad, Δθ_b = in-plane part of (ω2 - ω1) dt
};

[[nodiscard]] inline BondIncrements bond_increments(const ContactKinematics& k) noexcept {
  const Vec3& n = k.normal;
  const double vn = dot(k.relative_velocity, n);
  const double wn = dot(k.relative_angular_velocity, n);
  return {vn * k.dt, k.dt * (k.relative_velocity - vn * n), wn * k.dt, k.dt * (k.relative_angular_velocity - wn * n)};
}

/// A stored in-plane vector carried into the contact's current plane (tilt and twirl), magnitude kept.
[[nodiscard]] inline Vec3 load_in_plane(const double* h, const Vec3& normal, const ContactTwirl& twirl) noexcept {
  return turn_with_contact_plane(load_vec3(h), normal, twirl);
}

}  // namespace dfc::dem
