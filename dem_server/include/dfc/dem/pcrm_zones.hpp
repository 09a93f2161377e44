#pragma once
// Graded particle upscaling of a PCRM body (docs/dem_generation.md §7):
// zones, each filled with the one prepared REV scaled to the zone's S.
//
// Ciantia, Previtali, Zheng et al. (2024, §3) upscale the chalk by S = 2.1
// within 0.6 D of the pile axis, rising to 4.8 at 2.5 D: fine particles where
// the pile shears the rock, coarse ones where the strains are small.
//
// Filling a zone. The REV is prepared once, at the first zone's S. A zone of
// scale factor S_k is filled with its geometric copy scaled by s = S_k / S_0:
// centres, radii and the cell times s; each history column times s^e, e the
// length dimension of its unit (m: 1, N: 2, N m: 3, rad and "-": 0). With the
// law's parameters upscaled by S_k (contact_law_registry.hpp upscale: moduli
// and strengths fixed, softening lengths and gaps times S) this is the same
// packing in the same state: forces grow as s^2 with the areas, so every
// stress, the porosity and every bond's damage are the REV's (the upscaling
// rules make the REV at S and at s S the same body at two sizes; the tests
// check the law returns s^2 times the force of the scaled state).
//
// Membership. A sphere belongs to the first zone (in scenario order) whose
// region holds its centre; the last zone may omit its region and takes the
// rest of the body's region. Each zone's copies tile the box its region
// shares with the body's, starting at that box's corner.
//
// Seams (our rule). Spheres of two zones near a zone boundary overlap where
// their packings meet. The finer zone yields (smaller S; of equal S the later
// one), so that its holes are on its own, smaller scale: a sphere is removed
// when it overlaps a sphere of a coarser zone by more than
// `seam_overlap_fraction` of the smaller radius. The two packings then stand
// apart by up to a fine sphere, so the fine spheres are seated on the coarse
// packing: each one within its own radius of a coarser zone's sphere moves
// straight towards the nearest such sphere until it touches the first sphere
// in its way, and stays if that one is of a coarser zone (as
// boundary_seating.hpp seats a body on a wall, along a free path; bond loads
// are stored history, so the move leaves them as they are). The pairs across
// the seam within their pair law's bond gap are bonded with zero load at the
// first rebuild (Simulation::bond_across_materials_now), like the REV's own
// bonds when they formed. Their parameters are the mixed ones of the two
// zones (particle_materials.hpp).
#include <optional>
#include <vector>

#include "dfc/dem/bed_generator.hpp"
#include "dfc/dem/contact_model.hpp"
#include "dfc/dem/pcrm_replication.hpp"
#include "dfc/dem/rev_preparation.hpp"

namespace dfc::dem {

struct PcrmZone {
  double scale_factor = 1.0;         ///< S of the zone (absolute)
  std::optional<BedRegion> region;   ///< nullopt: the rest of the body's region (last zone only)
};

/// The REV scaled by s: lengths times s, history columns by their units'
/// length dimension. UserError for a column unit of unknown dimension.
[[nodiscard]] PreparedRev scaled_rev(const PreparedRev& rev, double s, const std::vector<HistoryColumn>& columns);

struct ZonedBody {
  ReplicatedBody body;                     ///< material = zone index
  std::vector<std::size_t> zone_spheres;   ///< spheres per zone, after the seams
  std::size_t seam_removed = 0;            ///< spheres removed at the seams
  std::size_t seam_seated = 0;             ///< spheres moved onto a coarser zone's packing
};

/// Fills `region` zone by zone (rule above) from `rev` prepared at
/// zones[0].scale_factor. Ids: zone k's ids follow zone k-1's (each zone's
/// ids are those of replicate()).
[[nodiscard]] ZonedBody replicate_zones(const PreparedRev& rev, const std::vector<HistoryColumn>& columns, const BedRegion& region,
                                        const std::vector<PcrmZone>& zones, double protrusion_fraction, double seam_overlap_fraction);

}  // namespace dfc::dem
