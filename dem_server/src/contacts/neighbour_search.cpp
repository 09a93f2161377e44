#include "dfc/dem/neighbour_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "dfc/common/errors.hpp"
#include "dfc/dem/parallel.hpp"
#include "dfc/dem/triangle_distance_bound.hpp"
#include "dfc/dem/triangle_geometry.hpp"

namespace dfc::dem {

std::array<std::int64_t, 3> CellGrid::cell_of(const Vec3& x) const noexcept {
  const double coordinate[3] = {x.x, x.y, x.z};
  const double corner[3] = {origin.x, origin.y, origin.z};
  std::array<std::int64_t, 3> c{};
  for (std::size_t a = 0; a < 3; ++a) {
    // Open axes: the cell of the lattice anchored at 0, an integer offset from
    // the grid's first cell (exact, whatever part of space the grid covers);
    // periodic axes: from the cell's lower face.
    const double k = periodic[a] ? std::floor((coordinate[a] - corner[a]) / cell_size) : std::floor(coordinate[a] / cell_size) - double(first_cell[a]);
    c[a] = !(k > 0.0) ? 0 : k >= double(dims[a] - 1) ? dims[a] - 1 : std::int64_t(k);  // also NaN: cell 0
  }
  return c;
}

namespace {

/// The grid over [lo, lo + extent] (open axes: the cells of the lattice
/// anchored at 0 that hold lo to lo + extent; periodic axes: floor(L/size)
/// cells spanning the cell exactly), and the order of the slots by (cell,
/// particle id): a counting sort by cell, then each cell's slots by id.
/// Cells along each axis of a grid of `size` over [lo, lo + extent].
std::array<double, 3> cells_along(double size, const Vec3& lo, const Vec3& extent, std::array<bool, 3> periodic) {
  const double low[3] = {lo.x, lo.y, lo.z};
  const double length[3] = {extent.x, extent.y, extent.z};
  std::array<double, 3> cells{};
  for (std::size_t a = 0; a < 3; ++a)
    cells[a] = periodic[a] ? std::max(1.0, std::floor(length[a] / size)) : std::floor((low[a] + length[a]) / size) - std::floor(low[a] / size) + 1.0;
  return cells;
}

/// The cell size of a grid over [lo, lo + extent] holding `count` particles:
/// min_cell_size, grown if needed to keep the cell count below ~4 per particle.
double grid_cell_size(double min_cell_size, const Vec3& lo, const Vec3& extent, std::array<bool, 3> periodic, std::size_t count) {
  double size = min_cell_size > 0.0 ? min_cell_size : 1.0;  // no particles with size: any cell will do
  const double max_cells = 4.0 * double(count) + 64.0;
  const auto total_cells = [&] {
    const auto c = cells_along(size, lo, extent, periodic);
    return c[0] * c[1] * c[2];
  };
  double total = total_cells();
  while (total > max_cells) {  // sparse or exploded packing: coarser cells
    size *= std::max(1.01, std::cbrt(total / max_cells));
    total = total_cells();
  }
  return size;
}

CellGrid build_grid(const ParticleStore& particles, double cell_size, const Vec3& lo, const Vec3& extent, std::array<bool, 3> periodic,
                    int threads, std::vector<std::uint32_t>& order) {
  const auto& positions = particles.position;
  CellGrid grid;
  grid.periodic = periodic;
  grid.cell_size = cell_size;
  const double low[3] = {lo.x, lo.y, lo.z};
  const auto along = cells_along(grid.cell_size, lo, extent, periodic);
  double corner[3]{};
  for (std::size_t a = 0; a < 3; ++a) {
    grid.dims[a] = std::int64_t(along[a]);
    grid.first_cell[a] = periodic[a] ? 0 : std::int64_t(std::floor(low[a] / grid.cell_size));
    corner[a] = periodic[a] ? low[a] : double(grid.first_cell[a]) * grid.cell_size;
  }
  grid.origin = {corner[0], corner[1], corner[2]};

  std::vector<std::uint32_t> cell(positions.size());
  grid.cell_start.assign(grid.cell_count() + 1, 0);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const auto c = grid.cell_of(positions[i]);
    cell[i] = std::uint32_t(grid.linear_index(c[0], c[1], c[2]));
    ++grid.cell_start[cell[i] + 1];
  }
  for (std::size_t c = 0; c < grid.cell_count(); ++c) grid.cell_start[c + 1] += grid.cell_start[c];
  order.resize(positions.size());
  std::vector<std::uint32_t> fill(grid.cell_start.begin(), grid.cell_start.end() - 1);
  for (std::size_t i = 0; i < positions.size(); ++i) order[fill[cell[i]]++] = std::uint32_t(i);
  // Within a cell by id, not by the slots' previous order: the order then
  // depends on the positions and ids alone, not on the history of the store.
  const auto cells = std::int64_t(grid.cell_count());
  const auto& id = particles.id;
#pragma omp parallel for schedule(static) num_threads(threads) if(std::int64_t(positions.size()) >= min_parallel_items)
  for (std::int64_t c = 0; c < cells; ++c) {
    const auto begin = order.begin() + std::ptrdiff_t(grid.cell_start[std::size_t(c)]);
    const auto end = order.begin() + std::ptrdiff_t(grid.cell_start[std::size_t(c) + 1]);
    if (end - begin > 1) std::sort(begin, end, [&](std::uint32_t a, std::uint32_t b) { return id[a] < id[b]; });
  }
  return grid;
}

/// Bounding box of the positions (throws SolverError on a non-finite one).
std::pair<Vec3, Vec3> position_bounds(std::span<const Vec3> positions) {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec3 hi = -lo;
  for (const auto& x : positions) {
    if (!is_finite(x)) throw SolverError("a particle position is not finite; the simulation has become unstable");
    lo = {std::min(lo.x, x.x), std::min(lo.y, x.y), std::min(lo.z, x.z)};
    hi = {std::max(hi.x, x.x), std::max(hi.y, x.y), std::max(hi.z, x.z)};
  }
  if (positions.empty()) lo = hi = Vec3{};
  return {lo, hi};
}

}  // namespace

CellGrid build_cell_grid(const ParticleStore& particles, double min_cell_size, int threads, std::vector<std::uint32_t>& order,
                         const BodyBounds* body) {
  const auto [lo, hi] = position_bounds(particles.position);
  constexpr std::array<bool, 3> open{false, false, false};
  const double size = body ? grid_cell_size(min_cell_size, body->lo, body->hi - body->lo, open, body->count)
                           : grid_cell_size(min_cell_size, lo, hi - lo, open, particles.size());
  return build_grid(particles, size, lo, hi - lo, open, threads, order);
}

CellGrid build_cell_grid(const ParticleStore& particles, double min_cell_size, const PeriodicCell& cell, int threads,
                         std::vector<std::uint32_t>& order) {
  auto [lo, hi] = position_bounds(particles.position);
  // Periodic axes span the cell; open axes the particles (they may leave the box there).
  const auto pick = [&](int a, double open_value, double cell_value) { return cell.periodic[std::size_t(a)] ? cell_value : open_value; };
  lo = {pick(0, lo.x, cell.lo.x), pick(1, lo.y, cell.lo.y), pick(2, lo.z, cell.lo.z)};
  hi = {pick(0, hi.x, cell.hi.x), pick(1, hi.y, cell.hi.y), pick(2, hi.z, cell.hi.z)};
  CellGrid grid = build_grid(particles, grid_cell_size(min_cell_size, lo, hi - lo, cell.periodic, particles.size()), lo, hi - lo, cell.periodic,
                             threads, order);
  grid.space = PeriodicSpace(cell);
  return grid;
}

namespace {

/// Calls visit(j) for every slot j > i in the 27 cells around particle i.
/// Periodic: indices on periodic axes wrap, and a cell reached twice (an axis
/// of 1 or 2 cells, where -1 and +1 are the same cell) is visited once, so
/// every pair is found once. Cells are visited in increasing index either way.
template <bool Periodic, class Visit>
void for_each_later_neighbour(const CellGrid& grid, const Vec3& xi, std::uint32_t i, Visit&& visit) {
  const auto c = grid.cell_of(xi);
  std::array<std::size_t, 27> cells{};
  std::size_t count = 0;
  const auto index = [&](std::size_t a, std::int64_t k) {
    if constexpr (Periodic) {
      if (grid.periodic[a]) return ((k % grid.dims[a]) + grid.dims[a]) % grid.dims[a];
    }
    return k;
  };
  for (std::int64_t dz = -1; dz <= 1; ++dz) {
    const std::int64_t z = index(2, c[2] + dz);
    if (z < 0 || z >= grid.dims[2]) continue;
    for (std::int64_t dy = -1; dy <= 1; ++dy) {
      const std::int64_t y = index(1, c[1] + dy);
      if (y < 0 || y >= grid.dims[1]) continue;
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        const std::int64_t x = index(0, c[0] + dx);
        if (x < 0 || x >= grid.dims[0]) continue;
        cells[count++] = grid.linear_index(x, y, z);
      }
    }
  }
  if constexpr (Periodic) {
    std::sort(cells.begin(), cells.begin() + std::ptrdiff_t(count));
    count = std::size_t(std::unique(cells.begin(), cells.begin() + std::ptrdiff_t(count)) - cells.begin());
  }
  // Slots are sorted by cell, so whole cells before i's own are skipped by j > i.
  for (std::size_t k = 0; k < count; ++k)
    for (std::uint32_t j = std::max(grid.cell_start[cells[k]], i + 1); j < grid.cell_start[cells[k] + 1]; ++j) visit(j);
}

/// Two passes (count, then fill at prefix-summed offsets): parallel, yet the
/// list is the same as a serial search would produce. `Space` gives the branch
/// vector (OpenSpace or the grid's PeriodicSpace).
template <bool Periodic, class Space>
void collect_pairs(const CellGrid& grid, const Space& space, const ParticleStore& particles, double skin, int threads,
                   std::vector<std::uint32_t>& first, std::vector<std::uint32_t>& second) {
  const auto n = static_cast<std::int64_t>(particles.size());
  const auto& x = particles.position;
  const auto& r = particles.radius;
  const auto near = [&](std::uint32_t i, std::uint32_t j) { return within_skin(space.branch(x[i], x[j]), r[i], r[j], skin); };
  const auto neighbours = [&](std::uint32_t i, auto&& visit) { for_each_later_neighbour<Periodic>(grid, x[i], i, visit); };
  std::vector<std::uint32_t> offset(std::size_t(n) + 1, 0);
#pragma omp parallel for schedule(dynamic, 256) num_threads(threads) if(n >= min_parallel_items)
  for (std::int64_t i = 0; i < n; ++i) {
    std::uint32_t count = 0;
    neighbours(std::uint32_t(i), [&](std::uint32_t j) { count += near(std::uint32_t(i), j) ? 1u : 0u; });
    offset[std::size_t(i) + 1] = count;
  }
  for (std::size_t i = 0; i < std::size_t(n); ++i) offset[i + 1] += offset[i];
  first.resize(offset.back());
  second.resize(offset.back());
#pragma omp parallel for schedule(dynamic, 256) num_threads(threads) if(n >= min_parallel_items)
  for (std::int64_t i = 0; i < n; ++i) {
    std::uint32_t at = offset[std::size_t(i)];
    neighbours(std::uint32_t(i), [&](std::uint32_t j) {
      if (!near(std::uint32_t(i), j)) return;
      first[at] = std::uint32_t(i);
      second[at] = j;
      ++at;
    });
  }
}

}  // namespace

void find_pair_candidates(const CellGrid& grid, const ParticleStore& particles, double skin, int threads, std::vector<std::uint32_t>& first,
                          std::vector<std::uint32_t>& second) {
  if (grid.periodic[0] || grid.periodic[1] || grid.periodic[2]) collect_pairs<true>(grid, grid.space, particles, skin, threads, first, second);
  else collect_pairs<false>(grid, OpenSpace{}, particles, skin, threads, first, second);
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> find_facet_candidates(const CellGrid& grid, const ParticleStore& particles,
                                                                           const Wall& wall, double skin, double r_max, int threads) {
  const auto n_facets = static_cast<std::int64_t>(wall.facet_count());
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> per_facet(static_cast<std::size_t>(n_facets));
  if (particles.size() == 0) return {};
  const Vec3 grid_hi = grid.origin + Vec3{double(grid.dims[0]), double(grid.dims[1]), double(grid.dims[2])} * grid.cell_size;
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads) if(n_facets * std::int64_t(particles.size()) >= min_parallel_items)
  for (std::int64_t f = 0; f < n_facets; ++f) {
    const auto& [ia, ib, ic] = wall.facets[std::size_t(f)];
    const Vec3 a = wall.vertices[ia], b = wall.vertices[ib], c = wall.vertices[ic];
    const double reach = r_max + skin;
    const TriangleDistanceBound bound(a, b, c);
    const Vec3 lo = Vec3{std::min({a.x, b.x, c.x}), std::min({a.y, b.y, c.y}), std::min({a.z, b.z, c.z})} - Vec3{reach, reach, reach};
    const Vec3 hi = Vec3{std::max({a.x, b.x, c.x}), std::max({a.y, b.y, c.y}), std::max({a.z, b.z, c.z})} + Vec3{reach, reach, reach};
    // A facet whose reach misses the particles' box has no candidates.
    if (hi.x < grid.origin.x || hi.y < grid.origin.y || hi.z < grid.origin.z || lo.x > grid_hi.x || lo.y > grid_hi.y || lo.z > grid_hi.z)
      continue;
    const auto c_lo = grid.cell_of(lo);
    const auto c_hi = grid.cell_of(hi);
    auto& out = per_facet[std::size_t(f)];
    for (std::int64_t z = c_lo[2]; z <= c_hi[2]; ++z)
      for (std::int64_t y = c_lo[1]; y <= c_hi[1]; ++y)
        for (std::int64_t x = c_lo[0]; x <= c_hi[0]; ++x) {
          const std::size_t cell = grid.linear_index(x, y, z);
          for (std::uint32_t p = grid.cell_start[cell]; p < grid.cell_start[cell + 1]; ++p) {
            const double particle_reach = particles.radius[p] + skin;
            // Most particles of the box lie beside a long, thin facet (a pile's
            // shaft): the bound rejects them without the closest point, and it
            // never rejects one the exact test below would keep.
            if (bound.certainly_beyond(particles.position[p], particle_reach)) continue;
            if (distance_to_triangle(particles.position[p], a, b, c) < particle_reach) out.emplace_back(p, std::uint32_t(f));
          }
        }
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> all;
  for (auto& list : per_facet) all.insert(all.end(), list.begin(), list.end());
  std::sort(all.begin(), all.end());  // keys are unique: the order is fixed
  return all;
}

}  // namespace dfc::dem
