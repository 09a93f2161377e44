#pragma once
// Stress carried by each particle, and its average over horizontal slices
// (docs/dem_generation.md §4).
//
// Per particle p (Love 1927; Weber 1966; Potyondy & Cundall 2004 §2.4 "average
// stress in a particle"):
//     sigma_p = -(1/V_p) sum_c f_c (x) (x_c - x_p),
// f_c the force ON p at contact point x_c, V_p = 4/3 pi r^3, compression
// positive. Summed over a volume V with its moments V_p sigma_p, the pair
// terms of two particles combine into -f (x) d (d the branch vector), so
//     sigma_V = (1/V) sum_{p in V} V_p sigma_p
// is the Love–Weber stress of the particles in V (their wall contacts
// included); for a slice of a region V is the slice of the region, voids
// included. Couples (bond moments) enter only through the forces.
#include <array>
#include <span>
#include <vector>

#include "dfc/dem/bed_generator.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

/// Order xx, xy, xz, yy, yz, zz (XDMF's Tensor6, as the continuum's zone_stress), Pa, compression positive.
using Stress6 = std::array<double, 6>;

/// Per particle slot, from the last force evaluation; zeros before the first step
/// or after a step that did not record complete contact outputs.
[[nodiscard]] std::vector<Stress6> particle_stress(const Simulation& simulation);

struct SliceProfile {
  std::vector<double> z;           ///< m, slice centres, top first
  std::vector<double> sigma_v;     ///< Pa, sigma_zz
  std::vector<double> sigma_h;     ///< Pa, (sigma_xx + sigma_yy) / 2
  std::vector<double> porosity;    ///< 1 - sphere volume in the slice / slice volume (by centres)
};

/// Love–Weber stress of the particles whose centres lie in each of `slices`
/// equal horizontal slices of `region`, its sides moved in by `margin` (m):
/// the body's outermost layer, thinned by trimming and pressed by the walls,
/// is left out so that the slices measure the body, not its boundary.
/// The slice sums are exact (exact_sum.hpp), so the profile does not depend
/// on the order of the particles: a body gathered by id from many processes
/// gives the bits of the body on one.
[[nodiscard]] SliceProfile slice_profile(const Simulation& simulation, const BedRegion& region, int slices, double margin = 0.0);
/// The same for particles given by their centres, radii and stresses (one row each).
[[nodiscard]] SliceProfile slice_profile(std::span<const Vec3> position, std::span<const double> radius, std::span<const Stress6> stress,
                                         const BedRegion& region, int slices, double margin = 0.0);

}  // namespace dfc::dem
