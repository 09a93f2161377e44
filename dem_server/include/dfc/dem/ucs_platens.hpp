#pragma once
// Uniaxial compression between two rigid platens: the axis, the height and the
// stress–strain measures of a UCS test (docs/dem_ucs.md).
//
// The loading axis is the unit vector a from the bottom platen's vertex
// centroid to the top platen's; the sample height is the platen separation
// H = (c_top - c_bottom) . a (a fixed at set-up, so a tilting platen does not
// change the axis the strain is measured along).
//   axial strain   ε_a = (H0 - H) / H0                        (compression positive)
//   axial stress   σ_a = ((F_top - F_bottom) . a) / (2 A)     (compression positive)
// F_top, F_bottom are the forces the particles exert ON the platens: in
// compression the top is pushed along +a and the bottom along -a, so both
// terms are positive; averaging the two platens cancels the inertial part of
// the sample's response to first order (equal and opposite when the sample is
// in equilibrium, different only by m ü). A is the sample cross-section.
#include <span>

#include "dfc/dem/vec3.hpp"

namespace dfc::dem {

/// Mean of the vertices (the centroid of a plane platen's square).
[[nodiscard]] Vec3 vertex_centroid(std::span<const Vec3> vertices);

struct PlatenAxis {
  Vec3 axis;                  ///< unit, bottom -> top
  double initial_height = 0;  ///< m, H0
};

/// Axis and initial separation of two platens; throws UserError if they coincide.
[[nodiscard]] PlatenAxis platen_axis(std::span<const Vec3> top_vertices, std::span<const Vec3> bottom_vertices);

/// m, current platen separation along the fixed axis.
[[nodiscard]] double platen_separation(const PlatenAxis& a, std::span<const Vec3> top_vertices, std::span<const Vec3> bottom_vertices);

/// -, ε_a = (H0 - H)/H0, compression positive.
[[nodiscard]] double axial_strain(const PlatenAxis& a, double separation) noexcept;

/// Pa, σ_a = ((F_top - F_bottom) . a) / (2 A), compression positive.
[[nodiscard]] double axial_stress(const PlatenAxis& a, const Vec3& force_on_top, const Vec3& force_on_bottom, double area) noexcept;

}  // namespace dfc::dem
