#pragma once
// The bond cross-section and the deformability method shared by the bonded
// laws (docs/theory/dem_contact_laws.md §2.1–2.2).
//
// A bond is a disc of elastic springs centred at the contact point in the
// contact plane: radius R̄ = λ min(R1, R2), area A = π R̄², second moment
// I = π R̄⁴ / 4, polar moment J = 2 I. Stiffnesses come from moduli (the PFC
// "deformability" method), so that under particle upscaling by S the moduli
// stay fixed and the stiffnesses follow the radii (docs/theory/upscaling_and_pcrm.md §1–2).
// A ball–facet contact uses the ball radius alone (dem_contact_laws.md §2.2).
#include <algorithm>
#include <numbers>

#include "dfc/dem/contact_model.hpp"

namespace dfc::dem {

struct BondSection {
  double radius = 0.0;  ///< m, R̄
  double area = 0.0;    ///< m², A
  double inertia = 0.0; ///< m⁴, I (bending)
  double polar = 0.0;   ///< m⁴, J = 2 I (twisting)
};

/// R_min and R1 + R2 of a contact; a facet (radius_second = 0) counts as the ball alone.
[[nodiscard]] inline double contact_min_radius(const ContactKinematics& k) noexcept {
  return k.radius_second > 0.0 ? std::min(k.radius_first, k.radius_second) : k.radius_first;
}
[[nodiscard]] inline double contact_radius_sum(const ContactKinematics& k) noexcept { return k.radius_first + k.radius_second; }

/// Reference §2.1: R̄ = λ R_min.
[[nodiscard]] inline BondSection bond_section(const ContactKinematics& k, double radius_multiplier) noexcept {
  const double r = radius_multiplier * contact_min_radius(k);
  const double area = std::numbers::pi * r * r;
  const double inertia = 0.25 * area * r * r;
  return {r, area, inertia, 2.0 * inertia};
}

/// Reference §2.2, linear part: k_n = π E* R_min² / (R1 + R2) [N/m].
[[nodiscard]] inline double deformability_kn(const ContactKinematics& k, double emod) noexcept {
  const double r = contact_min_radius(k);
  return std::numbers::pi * emod * r * r / contact_radius_sum(k);
}

/// Reference §2.2, bond part: k̄_n = Ē* / (R1 + R2) [Pa/m].
[[nodiscard]] inline double deformability_bond_kn(const ContactKinematics& k, double emod) noexcept { return emod / contact_radius_sum(k); }

/// Upper bound of π E* R_min² / (R1 + R2) over contacts with radii <= r_max:
/// π E* r_max for a ball–facet contact (twice the equal-pair value).
[[nodiscard]] inline double deformability_kn_bound(double emod, double radius_max) noexcept { return std::numbers::pi * emod * radius_max; }

}  // namespace dfc::dem
