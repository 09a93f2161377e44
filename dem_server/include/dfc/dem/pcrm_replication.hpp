#pragma once
// Periodic cell replication (PCRM; Ciantia et al. 2017, doi 10.1051/epjconf/201714015012,
// and 2018, doi 10.1680/jencm.18.00025): a prepared REV is tiled in x, y and
// z to fill a region, with every pair's history (docs/dem_generation.md §2).
//
// Seams: the REV is periodic, so a pair that crosses a face of the cell joins
// sphere `first` of one copy to sphere `second` of the neighbouring copy
// (RevPair::image). The tiled body therefore has the REV's contacts and bonds
// everywhere, across the copies' faces too: no weak planes.
//
// Ids: copy c of REV sphere i gets id i * copies + c. Ids then order pairs as
// in the REV (i < j gives a smaller id for every copy), so a history row,
// stored "on the first body", is copied unchanged.
//
// Trimming: a sphere is kept when it lies inside the region, protruding
// through its boundary by at most `protrusion_fraction` of its radius (0: the
// whole sphere inside). A pair is kept when both spheres are.
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "dfc/dem/bed_generator.hpp"
#include "dfc/dem/contact_lists.hpp"
#include "dfc/dem/rev_preparation.hpp"

namespace dfc::dem {

struct ReplicatedBody {
  std::vector<std::int64_t> id;          ///< per sphere
  std::vector<GeneratedSphere> spheres;
  std::vector<std::uint16_t> material;   ///< per sphere: the zone of a graded body (pcrm_zones.hpp), else 0
  std::size_t stride = 0;
  std::vector<std::array<std::uint32_t, 2>> pairs;  ///< indices into spheres (first has the smaller id)
  std::vector<double> rows;              ///< pairs.size() * stride
  std::array<int, 3> copies{};           ///< copies along x, y, z

  /// The pair history keyed by particle ids, for Simulation::seed_pair_history.
  [[nodiscard]] HistoryArchive archive() const;
  /// The same archive, its rows taken rather than copied, and every array of
  /// the body released (not merely emptied: `v = {}` keeps the storage). For
  /// the model builder once the simulation holds the spheres: the paper
  /// model's 0.4 GB of rows then exist once, not twice, while its lists are
  /// first built.
  [[nodiscard]] HistoryArchive release_into_archive();
};

/// Smallest distance by which `sphere` may move outward before it leaves
/// `region`, minus its radius: >= 0 when the whole sphere is inside.
[[nodiscard]] double clearance(const GeneratedSphere& sphere, const BedRegion& region) noexcept;

/// `periodic`: the region is itself a periodic cell of whole copies (a box of
/// n L): pairs that leave the last copy join the first (a 2 x 2 x 2 REV).
[[nodiscard]] ReplicatedBody replicate(const PreparedRev& rev, const BedRegion& region, double protrusion_fraction, bool periodic = false);

/// The copies tile the box [lo, hi] from lo (as many as cover it); a placed
/// sphere is kept when `keep` says so (replicate() above keeps those inside
/// the region by the protrusion rule).
[[nodiscard]] ReplicatedBody replicate(const PreparedRev& rev, const Vec3& lo, const Vec3& hi, const std::function<bool(const GeneratedSphere&)>& keep,
                                       bool periodic = false);

/// Copies of a REV cell `cell_length` long along x, y, z that tile the box [lo, hi] from lo.
[[nodiscard]] std::array<int, 3> copies_to_cover(const Vec3& cell_length, const Vec3& lo, const Vec3& hi);

/// replicate(rev, lo, hi, keep, periodic), appended to `body` (of the same
/// stride) as material `material` with ids shifted by `id_offset`; returns
/// this part's copies. Why appended in place: the zones of a graded body
/// (pcrm_zones.hpp) went through a body of their own each, copied into the
/// whole, and the paper model's 0.4 GB of rows then existed two and three
/// times over (the largest part of its peak memory).
std::array<int, 3> replicate_into(ReplicatedBody& body, const PreparedRev& rev, const Vec3& lo, const Vec3& hi,
                                  const std::function<bool(const GeneratedSphere&)>& keep, std::uint16_t material, std::int64_t id_offset,
                                  bool periodic = false);

/// Room in `body` for `pairs` more pairs and `spheres` more spheres, so that
/// appending them copies nothing. An upper bound costs address space, not
/// memory: the pages no row reaches are never touched.
void reserve_room(ReplicatedBody& body, std::size_t spheres, std::size_t pairs);

}  // namespace dfc::dem
