#pragma once
// Linked-cell neighbour search with a Verlet skin (Allen & Tildesley,
// Computer Simulation of Liquids, 2nd ed. 2017, §5.3–5.4).
//
// Candidates are pairs closer than r_i + r_j + skin at build time; they stay
// valid while no particle has moved more than skin/2 (the rebuild rule in
// simulation.cpp). Both searches produce their lists in an order fixed by the
// slots alone, whatever the thread count, so the force sums built on them are
// reproducible bit for bit.
//
// The slot order itself is canonical: by the cell of a lattice anchored at
// the origin of space (cells of the grid's size), then by particle id. Two
// stores holding the same particles near a place (the whole body, or the part
// with its halo that one process of a decomposed run holds) order them alike,
// whatever order they came in, so each particle meets its partners in the
// same order and its force sum has the same bits (issue "Beyond one machine";
// tests CanonicalOrder.*). What must agree for that: the cell size (from the
// largest radius and the skin of the whole body) and, on periodic axes, the
// periodic cell.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "dfc/dem/particle_store.hpp"
#include "dfc/dem/periodic_cell.hpp"
#include "dfc/dem/wall.hpp"

namespace dfc::dem {

struct CellGrid {
  Vec3 origin;             ///< m, corner of cell (0,0,0)
  /// Open axes: the index along the lattice anchored at 0 of cell 0 (origin =
  /// first_cell x cell_size); periodic axes: 0.
  std::array<std::int64_t, 3> first_cell{0, 0, 0};
  double cell_size = 0.0;  ///< m, >= 2 r_max + skin so that only adjacent cells can hold partners
  std::array<std::int64_t, 3> dims{1, 1, 1};
  /// Periodic axes: the grid spans the cell exactly (the last cell takes the
  /// remainder, so every cell is at least cell_size wide), cell dims-1 is the
  /// neighbour of cell 0, and distances are minimum images (`space`).
  std::array<bool, 3> periodic{false, false, false};
  PeriodicSpace space;
  /// Particles of cell c are slots [cell_start[c], cell_start[c+1]) once the
  /// particles are ordered by `order` (build_cell_grid).
  std::vector<std::uint32_t> cell_start;

  [[nodiscard]] std::size_t cell_count() const noexcept { return std::size_t(dims[0] * dims[1] * dims[2]); }
  /// Cell coordinates of x, clamped into the grid.
  [[nodiscard]] std::array<std::int64_t, 3> cell_of(const Vec3& x) const noexcept;
  [[nodiscard]] std::size_t linear_index(std::int64_t ix, std::int64_t iy, std::int64_t iz) const noexcept {
    return std::size_t((iz * dims[1] + iy) * dims[0] + ix);
  }
};

/// The extent of a whole body (a decomposed run's parts build their grids
/// with the cell size the whole body's grid would have).
struct BodyBounds {
  Vec3 lo, hi;            ///< m, bounding box of the particle centres
  std::size_t count = 0;  ///< particles
};

/// Grid over the bounding box of the particles with cells of at least
/// `min_cell_size` (grown if needed to keep the cell count below ~4 per
/// particle, so a particle flying away cannot exhaust memory). `order`
/// receives the slots in the canonical order, by cell, then by id (on
/// `threads`): new slot k = old slot order[k].
/// With `body`, the cell size is the one the whole body's grid would take
/// (its coarsening decided by the body's extent and count, not this part's).
[[nodiscard]] CellGrid build_cell_grid(const ParticleStore& particles, double min_cell_size, int threads, std::vector<std::uint32_t>& order,
                                       const BodyBounds* body = nullptr);
/// The same in a periodic cell: on its periodic axes the grid spans [lo, hi)
/// (positions must be wrapped); on its open axes the particles' extent.
[[nodiscard]] CellGrid build_cell_grid(const ParticleStore& particles, double min_cell_size, const PeriodicCell& cell, int threads,
                                       std::vector<std::uint32_t>& order);

/// Whether two spheres `branch` apart (centre to centre) are candidates:
/// |branch| < r_i + r_j + skin, the test of find_pair_candidates.
[[nodiscard]] inline bool within_skin(const Vec3& branch, double r_i, double r_j, double skin) noexcept {
  const double reach = r_i + r_j + skin;
  return norm2(branch) < reach * reach;
}

/// Candidate pairs (i < j by slot) with |x_i - x_j| < r_i + r_j + skin
/// (the minimum image on a periodic grid's periodic axes).
/// The particles must be in grid order. Output order: by i, then by the
/// cell stencil and slot of j.
void find_pair_candidates(const CellGrid& grid, const ParticleStore& particles, double skin, int threads, std::vector<std::uint32_t>& first,
                          std::vector<std::uint32_t>& second);

/// Candidate (particle slot, facet) pairs of `wall` with distance(centre,
/// facet) < r + skin, sorted by particle then facet. `r_max` bounds the radii.
[[nodiscard]] std::vector<std::pair<std::uint32_t, std::uint32_t>> find_facet_candidates(const CellGrid& grid, const ParticleStore& particles,
                                                                                         const Wall& wall, double skin, double r_max,
                                                                                         int threads);

}  // namespace dfc::dem
