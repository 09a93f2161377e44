#include "dfc/dem/boundary_seating.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <vector>

#include "dfc/common/errors.hpp"
#include "dfc/dem/triangle_geometry.hpp"

namespace dfc::dem {

namespace {

/// Particle slots hashed by a cubic grid of edge `cell`.
class SlotGrid {
 public:
  SlotGrid(const std::vector<Vec3>& centres, double cell) : cell_(cell) {
    for (std::size_t i = 0; i < centres.size(); ++i) cells_[pack(index(centres[i]))].push_back(std::uint32_t(i));
  }
  /// Calls f(j) for every slot in the cells within `reach` (m) of x.
  template <class F>
  void around(const Vec3& x, double reach, F&& f) const {
    const auto span = std::int64_t(std::ceil(reach / cell_));
    const auto c = index(x);
    for (std::int64_t a = c[0] - span; a <= c[0] + span; ++a)
      for (std::int64_t b = c[1] - span; b <= c[1] + span; ++b)
        for (std::int64_t d = c[2] - span; d <= c[2] + span; ++d)
          if (const auto it = cells_.find(pack({a, b, d})); it != cells_.end())
            for (const std::uint32_t j : it->second) f(j);
  }

 private:
  [[nodiscard]] std::array<std::int64_t, 3> index(const Vec3& x) const {
    return {std::int64_t(std::floor(x.x / cell_)), std::int64_t(std::floor(x.y / cell_)), std::int64_t(std::floor(x.z / cell_))};
  }
  [[nodiscard]] static std::int64_t pack(const std::array<std::int64_t, 3>& c) {
    return ((c[0] & 0x1fffff) << 42) | ((c[1] & 0x1fffff) << 21) | (c[2] & 0x1fffff);
  }
  double cell_;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells_;
};

/// Nearest point of the wall to x.
Vec3 nearest_point(const Vec3& x, const Wall& wall) {
  Vec3 best;
  double best_d2 = INFINITY;
  for (const auto& f : wall.facets) {
    const Vec3 p = closest_point_on_triangle(x, wall.vertices[f[0]], wall.vertices[f[1]], wall.vertices[f[2]]).point;
    const double d2 = norm2(p - x);
    if (d2 < best_d2) {
      best_d2 = d2;
      best = p;
    }
  }
  return best;
}

}  // namespace

FaceAreas face_areas(const BedRegion& r) {
  if (r.shape == BedRegion::Shape::box) {
    const Vec3 l = r.max - r.min;
    return {l.x * l.y, 2.0 * (l.x + l.y) * l.z};
  }
  return {std::numbers::pi * r.radius * r.radius, 2.0 * std::numbers::pi * r.radius * (r.z_max - r.z_min)};
}

SeatingReport seat_on_wall(Simulation& sim, const Wall& wall, const StressProfile& profile, const FaceAreas& faces) {
  if (sim.step_count() != 0) throw UserError("a generated body is seated on its walls before the first step only");
  SeatingReport report;
  ParticleStore& p = sim.particles_for_edit();
  double r_max = 0.0;
  for (const double r : p.radius) r_max = std::max(r_max, r);
  // Candidates: spheres within a diameter of the wall, nearest first (one that
  // moves first may then block one behind it). The wall's bounding box, grown
  // by 2 r_max, rejects the others cheaply.
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (const Vec3& v : wall.vertices) {
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  const double margin = 3.0 * r_max;
  std::vector<std::pair<double, std::uint32_t>> order;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    if (x.x < lo.x - margin || x.x > hi.x + margin || x.y < lo.y - margin || x.y > hi.y + margin || x.z < lo.z - margin || x.z > hi.z + margin)
      continue;
    const double gap = norm(nearest_point(x, wall) - x) - p.radius[i];
    if (gap < 2.0 * r_max) order.emplace_back(gap, std::uint32_t(i));
  }
  std::sort(order.begin(), order.end());
  // Pass 1: the spheres whose path to the wall is free, and where they touch it.
  struct Seat {
    std::uint32_t slot;
    Vec3 normal;   ///< towards the wall
    double travel;  ///< m, to touch (< 0: backing off an overlap)
    bool facing_floor;
  };
  std::vector<Seat> seats;
  std::size_t on_floor = 0;
  const SlotGrid grid(p.position, 2.0 * r_max);
  for (const auto& [gap, i] : order) {
    const Vec3 x = p.position[i];
    const double r = p.radius[i];
    const Vec3 towards = nearest_point(x, wall) - x;
    const double distance = norm(towards);
    if (!(distance > 0.0)) continue;  // its centre on the wall: cut, removed by the trimming
    const Vec3 n = (1.0 / distance) * towards;
    // < 0: it overlaps the wall already (the trimming keeps a sphere cut by
    // up to wall_contact_overlap_fraction of its radius). It backs off to
    // touching, then presses like the others: left so, its overlap (up to
    // 1e-3 r, a force k_n 1e-3 r of about 1 N on the chalk at S = 10) would
    // not follow the g-level and swamped sigma_h at low g (measured: +860 %
    // at 1 g on one packing of the small chalk model). The move, at most
    // 1e-3 r, is too small to check for neighbours: the pairs that close
    // are bonded, whose load is stored history.
    const double travel = distance - r;
    const Vec3 target = x + travel * n;
    bool blocked = false;
    if (travel > 0.0)
      grid.around(target, travel + r + r_max, [&](std::uint32_t j) {
        if (j == i || blocked) return;
        const double reach = r + p.radius[j];
        const double before = norm(p.position[j] - x), after = norm(p.position[j] - target);
        blocked = after < reach && after < before;
      });
    if (blocked) continue;
    p.position[i] = target;  // the grid keeps the old cell: at most a diameter away, within the search reach
    const bool floor = std::abs(n.z) > std::sqrt(0.5);
    on_floor += floor ? 1 : 0;
    seats.push_back({i, n, travel, floor});
  }
  // Pass 2: each seated sphere presses with its share of the face's force,
  // the face area divided among the spheres seated on it.
  const std::size_t on_sides = seats.size() - on_floor;
  for (const Seat& seat : seats) {
    const std::size_t count = seat.facing_floor ? on_floor : on_sides;
    const double area = (seat.facing_floor ? faces.floor : faces.sides) / double(count);
    Vec3& x = p.position[seat.slot];
    const double stress = seat.facing_floor ? profile.vertical(x.z) : profile.horizontal(x.z);
    const double overlap = stress * area / wall.law.stiffness_bound(p.radius[seat.slot]).normal;
    x += overlap * seat.normal;
    ++report.seated;
    report.largest_move = std::max(report.largest_move, std::abs(seat.travel + overlap));
  }
  return report;
}

}  // namespace dfc::dem
