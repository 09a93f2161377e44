#include "dfc/dem/pcrm_zones.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include "dfc/common/errors.hpp"
#include "dfc/dem/region_config.hpp"

namespace dfc::dem {

namespace {

/// Length dimension of a history column's unit under a geometric scaling
/// that keeps stresses: a displacement scales as s, a force as s^2 (stress
/// times area), a moment as s^3, a rotation and a ratio not at all.
int length_dimension(const std::string& unit) {
  if (unit == "m") return 1;
  if (unit == "N") return 2;
  if (unit == "N m") return 3;
  if (unit == "rad" || unit == "-") return 0;
  throw UserError("a history column has the unit \"" + unit + "\", whose scaling with the particle size is not known to the zone filling");
}

bool holds_centre(const BedRegion& region, const Vec3& x) { return clearance(GeneratedSphere{x, 0.0}, region) >= 0.0; }

/// Removes the spheres marked in `removed` with their pairs, compacting the
/// arrays in place (a copy of the kept body would hold the rows twice).
void remove_spheres(ReplicatedBody& body, const std::vector<bool>& removed) {
  std::vector<std::int64_t> new_index(body.spheres.size(), -1);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < body.spheres.size(); ++i) {
    if (removed[i]) continue;
    new_index[i] = std::int64_t(kept);
    body.id[kept] = body.id[i];
    body.spheres[kept] = body.spheres[i];
    body.material[kept] = body.material[i];
    ++kept;
  }
  body.id.resize(kept);
  body.spheres.resize(kept);
  body.material.resize(kept);
  // Pair k moves to slot kept_pairs <= k: a row is only ever copied downwards, onto one already moved.
  std::size_t kept_pairs = 0;
  for (std::size_t k = 0; k < body.pairs.size(); ++k) {
    const std::int64_t a = new_index[body.pairs[k][0]], b = new_index[body.pairs[k][1]];
    if (a < 0 || b < 0) continue;
    body.pairs[kept_pairs] = {std::uint32_t(a), std::uint32_t(b)};
    if (kept_pairs != k) std::copy_n(body.rows.begin() + std::ptrdiff_t(k * body.stride), body.stride, body.rows.begin() + std::ptrdiff_t(kept_pairs * body.stride));
    ++kept_pairs;
  }
  body.pairs.resize(kept_pairs);
  body.rows.resize(kept_pairs * body.stride);
}

/// Spheres hashed by cells of edge 2 r_max (each sphere in its centre's
/// cell): the candidates within reach of a point lie in the 5 x 5 x 5 cells
/// around it for reaches up to 4 r_max.
class SphereGrid {
 public:
  explicit SphereGrid(double r_max) : edge_(2.0 * r_max) {}
  void insert(std::uint32_t i, const Vec3& x) { cells_[key(x, 0, 0, 0)].push_back(i); }
  void erase(std::uint32_t i, const Vec3& x) {
    auto& list = cells_[key(x, 0, 0, 0)];
    list.erase(std::find(list.begin(), list.end(), i));
  }
  /// Calls visit(j) for every sphere of the cells within two of x's.
  template <class Visit>
  void near(const Vec3& x, Visit&& visit) const {
    for (int dz = -2; dz <= 2; ++dz)
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const auto it = cells_.find(key(x, dx, dy, dz));
          if (it == cells_.end()) continue;
          for (const std::uint32_t j : it->second) visit(j);
        }
  }

 private:
  [[nodiscard]] std::uint64_t key(const Vec3& x, int dx, int dy, int dz) const {
    const auto cell = [&](double v, int d) { return std::uint64_t((std::int64_t(std::floor(v / edge_)) + d) & 0x1fffff); };
    return cell(x.x, dx) | (cell(x.y, dy) << 21) | (cell(x.z, dz) << 42);
  }
  double edge_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

double surface_gap(const GeneratedSphere& a, const GeneratedSphere& b) { return norm(a.centre - b.centre) - a.radius - b.radius; }

/// Which zone yields at a seam: the finer one (smaller S; of equal S, the
/// later). Its holes are then on its own, smaller scale.
struct SeamRank {
  const std::vector<PcrmZone>& zones;
  /// True if a sphere of zone a stays where it meets one of zone b.
  [[nodiscard]] bool above(std::uint16_t a, std::uint16_t b) const noexcept {
    return zones[a].scale_factor > zones[b].scale_factor || (zones[a].scale_factor == zones[b].scale_factor && a < b);
  }
};

/// Spheres with the coarsest zone first (SeamRank), their order within a zone kept.
std::vector<std::uint32_t> seam_order(const ReplicatedBody& body, const SeamRank& rank) {
  std::vector<std::uint32_t> order(body.spheres.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = std::uint32_t(i);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return rank.above(body.material[a], body.material[b]); });
  return order;
}

/// Marks each sphere that overlaps a kept sphere of a coarser zone by more
/// than `fraction` of the smaller radius. Spheres are visited coarsest zone
/// first, so a removed sphere never removes another.
std::size_t mark_seam_overlaps(const ReplicatedBody& body, const SeamRank& rank, double r_max, double fraction, std::vector<bool>& removed) {
  SphereGrid grid(r_max);
  std::size_t count = 0;
  for (const std::uint32_t i : seam_order(body, rank)) {
    const GeneratedSphere& s = body.spheres[i];
    bool cut = false;
    grid.near(s.centre, [&](std::uint32_t j) {
      const GeneratedSphere& t = body.spheres[j];
      cut = cut || (rank.above(body.material[j], body.material[i]) && -surface_gap(s, t) > fraction * std::min(s.radius, t.radius));
    });
    if (cut) {
      removed[i] = true;
      ++count;
    } else {
      grid.insert(i, s.centre);
    }
  }
  return count;
}

/// Distance t >= 0 that a sphere (centre c, radius r) moves along the unit
/// vector u before it touches the sphere `other`; infinity if it never does.
/// A pair that already overlaps (neighbours in the REV's packing) limits the
/// move only where it would deepen: to an overlap of `fraction` of the smaller
/// radius (the seam's own tolerance), 0 if it is already deeper. Unlimited,
/// a seated sphere was driven into its neighbour by up to its gap to the
/// coarse sphere, close to a radius (an overlap the first step refuses).
double distance_to_touch(const Vec3& c, double r, const Vec3& u, const GeneratedSphere& other, double fraction) {
  const Vec3 d = other.centre - c;
  const double reach = r + other.radius, along = dot(d, u), across2 = norm2(d) - along * along;
  if (along <= 0.0) return std::numeric_limits<double>::infinity();
  if (norm2(d) <= reach * reach) {
    const double deep = reach - fraction * std::min(r, other.radius);  // centre distance at the tolerated overlap
    if (norm2(d) <= deep * deep) return 0.0;
    if (across2 >= deep * deep) return std::numeric_limits<double>::infinity();
    return along - std::sqrt(deep * deep - across2);
  }
  if (across2 >= reach * reach) return std::numeric_limits<double>::infinity();
  return along - std::sqrt(reach * reach - across2);
}

/// Seats the seam: each sphere with a sphere of a coarser zone less than
/// its own radius away moves straight towards the nearest such sphere until
/// it touches the first sphere in its way; it stays there if that sphere is
/// of a coarser zone (it is seated), and goes back otherwise (as
/// boundary_seating.hpp seats a body on a wall: only along a free path; a
/// neighbour it already overlaps stops it where the overlap reaches `fraction`
/// of the smaller radius).
/// Trimming and the seam's removals leave the two packings up to a sphere
/// apart; seated, they touch, and the first step bonds them. Bond loads are
/// stored history, so moving a sphere leaves them as they are.
std::size_t seat_seam(ReplicatedBody& body, const SeamRank& rank, double r_max, double fraction) {
  SphereGrid grid(r_max);
  const std::vector<std::uint32_t> order = seam_order(body, rank);
  for (const std::uint32_t i : order) grid.insert(i, body.spheres[i].centre);
  std::size_t seated = 0;
  for (const std::uint32_t i : order) {
    GeneratedSphere& s = body.spheres[i];
    std::int64_t nearest = -1;
    double gap = s.radius;
    grid.near(s.centre, [&](std::uint32_t j) {
      if (!rank.above(body.material[j], body.material[i])) return;
      const double g = surface_gap(s, body.spheres[j]);
      if (g < gap) gap = g, nearest = j;
    });
    if (nearest < 0 || gap <= 0.0) continue;
    const Vec3 to = body.spheres[std::size_t(nearest)].centre - s.centre;
    const Vec3 u = (1.0 / norm(to)) * to;
    double travel = std::numeric_limits<double>::infinity();
    std::int64_t first_hit = -1;
    grid.near(s.centre, [&](std::uint32_t j) {
      if (j == i) return;
      const double t = distance_to_touch(s.centre, s.radius, u, body.spheres[j], fraction);
      if (t < travel) travel = t, first_hit = j;
    });
    if (first_hit < 0 || !rank.above(body.material[std::size_t(first_hit)], body.material[i]) || travel > gap * (1.0 + 1e-9)) continue;
    grid.erase(i, s.centre);
    s.centre = s.centre + travel * u;
    grid.insert(i, s.centre);
    ++seated;
  }
  return seated;
}

}  // namespace

PreparedRev scaled_rev(const PreparedRev& rev, double s, const std::vector<HistoryColumn>& columns) {
  if (s == 1.0) return rev;
  PreparedRev out = rev;
  out.cell.lo = s * rev.cell.lo;
  out.cell.hi = s * rev.cell.hi;
  for (auto& sphere : out.spheres) {
    sphere.centre = s * sphere.centre;
    sphere.radius *= s;
  }
  std::vector<double> factor(columns.size());
  for (std::size_t c = 0; c < columns.size(); ++c) factor[c] = std::pow(s, length_dimension(columns[c].unit));
  for (std::size_t k = 0; k < out.pairs.size(); ++k)
    for (std::size_t c = 0; c < out.stride; ++c) out.rows[k * out.stride + c] *= factor[c];
  return out;
}

ZonedBody replicate_zones(const PreparedRev& rev, const std::vector<HistoryColumn>& columns, const BedRegion& region,
                          const std::vector<PcrmZone>& zones, double protrusion_fraction, double seam_overlap_fraction) {
  ZonedBody out;
  out.body.stride = rev.stride;
  const auto [body_lo, body_hi] = region_bounds(region);
  // Each zone's box, its REV's cell, and room for every copy of every zone:
  // the zones are then appended to one body without copying it.
  std::vector<std::array<Vec3, 2>> boxes;
  std::size_t sphere_bound = 0, pair_bound = 0;
  for (std::size_t k = 0; k < zones.size(); ++k) {
    const BedRegion& zone_region = zones[k].region ? *zones[k].region : region;
    const auto [zone_lo, zone_hi] = region_bounds(zone_region);
    const Vec3 lo{std::max(zone_lo.x, body_lo.x), std::max(zone_lo.y, body_lo.y), std::max(zone_lo.z, body_lo.z)};
    const Vec3 hi{std::min(zone_hi.x, body_hi.x), std::min(zone_hi.y, body_hi.y), std::min(zone_hi.z, body_hi.z)};
    if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z))
      throw ConfigError("particles.zones[" + std::to_string(k) + "].region", "the zone does not meet particles.region");
    boxes.push_back({lo, hi});
    const double s = zones[k].scale_factor / zones.front().scale_factor;
    const Vec3 cell_length = s == 1.0 ? rev.cell.length() : s * rev.cell.hi - s * rev.cell.lo;  // as scaled_rev scales the cell
    const auto copies = copies_to_cover(cell_length, lo, hi);
    const auto count = std::size_t(copies[0]) * std::size_t(copies[1]) * std::size_t(copies[2]);
    sphere_bound += count * rev.spheres.size();
    pair_bound += count * rev.pairs.size();
  }
  reserve_room(out.body, sphere_bound, pair_bound);
  std::int64_t id_offset = 0;
  for (std::size_t k = 0; k < zones.size(); ++k) {
    const BedRegion& zone_region = zones[k].region ? *zones[k].region : region;
    const PreparedRev zone_rev = scaled_rev(rev, zones[k].scale_factor / zones.front().scale_factor, columns);
    const auto keep = [&](const GeneratedSphere& s) {
      if (clearance(s, region) < -protrusion_fraction * s.radius || !holds_centre(zone_region, s.centre)) return false;
      for (std::size_t e = 0; e < k; ++e)
        if (holds_centre(*zones[e].region, s.centre)) return false;
      return true;
    };
    const auto copies = replicate_into(out.body, zone_rev, boxes[k][0], boxes[k][1], keep, std::uint16_t(k), id_offset);
    if (k == 0) out.body.copies = copies;
    id_offset += std::int64_t(rev.spheres.size()) * copies[0] * copies[1] * copies[2];
  }
  double r_max = 0.0;
  for (const auto& s : out.body.spheres) r_max = std::max(r_max, s.radius);
  std::vector<bool> removed(out.body.spheres.size(), false);
  const SeamRank rank{zones};
  out.seam_removed = mark_seam_overlaps(out.body, rank, r_max, seam_overlap_fraction, removed);
  if (out.seam_removed > 0) remove_spheres(out.body, removed);
  out.seam_seated = seat_seam(out.body, rank, r_max, seam_overlap_fraction);
  out.zone_spheres.assign(zones.size(), 0);
  for (const auto m : out.body.material) ++out.zone_spheres[m];
  return out;
}

}  // namespace dfc::dem
