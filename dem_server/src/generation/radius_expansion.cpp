#include "dfc/dem/radius_expansion.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "dfc/common/errors.hpp"
#include "dfc/common/work_progress.hpp"
#include "dfc/dem/cell_stress.hpp"
#include "dfc/dem/pcrm_replication.hpp"
#include "dfc/dem/portable_random.hpp"
#include "dfc/dem/region_config.hpp"

namespace dfc::dem {

namespace {

double sphere_volume(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }

/// Uniform buckets over the cell for the overlap test of the placement:
/// each is at least one largest diameter wide, so an overlapping partner is
/// in the 27 buckets around (wrapped on periodic axes, deduplicated).
class PlacementGrid {
 public:
  PlacementGrid(const PeriodicCell& cell, double min_size) : cell_(cell) {
    const Vec3 l = cell.length();
    const double e[3] = {l.x, l.y, l.z};
    for (std::size_t a = 0; a < 3; ++a) dims_[a] = std::max<std::int64_t>(1, std::int64_t(e[a] / min_size));
    size_ = {l.x / double(dims_[0]), l.y / double(dims_[1]), l.z / double(dims_[2])};
    buckets_.resize(std::size_t(dims_[0] * dims_[1] * dims_[2]));
  }
  void add(std::uint32_t k, const Vec3& x) { buckets_[index(cell_of(x))].push_back(k); }
  template <class Visit>
  void for_each_near(const Vec3& x, Visit&& visit) const {
    const auto c = cell_of(x);
    std::vector<std::size_t> seen;
    for (std::int64_t dz = -1; dz <= 1; ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          const std::array<std::int64_t, 3> n{c[0] + dx, c[1] + dy, c[2] + dz};
          std::array<std::int64_t, 3> w{};
          bool inside = true;
          for (std::size_t a = 0; a < 3; ++a) {
            w[a] = cell_.periodic[a] ? ((n[a] % dims_[a]) + dims_[a]) % dims_[a] : n[a];
            inside = inside && w[a] >= 0 && w[a] < dims_[a];
          }
          if (inside) seen.push_back(index(w));
        }
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
    for (const auto b : seen)
      for (const auto k : buckets_[b]) visit(k);
  }

 private:
  [[nodiscard]] std::array<std::int64_t, 3> cell_of(const Vec3& x) const {
    const Vec3 r = x - cell_.lo;
    const double v[3] = {r.x / size_.x, r.y / size_.y, r.z / size_.z};
    std::array<std::int64_t, 3> c{};
    for (std::size_t a = 0; a < 3; ++a) c[a] = std::clamp<std::int64_t>(std::int64_t(std::floor(v[a])), 0, dims_[a] - 1);
    return c;
  }
  [[nodiscard]] std::size_t index(const std::array<std::int64_t, 3>& c) const { return std::size_t((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]); }

  PeriodicCell cell_;
  std::array<std::int64_t, 3> dims_{1, 1, 1};
  Vec3 size_;
  std::vector<std::vector<std::uint32_t>> buckets_;
};

}  // namespace

double stage_radius(double final_radius, double multiplier, int stage, int stages) noexcept {
  if (stage >= stages) return final_radius;  // exactly: the target porosity is hit to round-off
  return final_radius * std::pow(multiplier, double(stage) / double(stages) - 1.0);
}

namespace {

/// Steps 1-2 in `cell` for a container of `volume`; `inside` (if set) rejects
/// a candidate position that the container does not hold whole.
ExpansionPacking place(const RadiusExpansionSpec& spec, const PeriodicCell& cell, double container_volume,
                       const std::function<bool(const GeneratedSphere&)>& inside) {
  PortableRandom random(spec.seed);
  ExpansionPacking out;
  // 1. Radii with the exact solid volume (1 - n) V.
  const double solid = (1.0 - spec.porosity) * container_volume;
  double volume = 0.0;
  while (volume < solid) {
    out.final_radius.push_back(random.uniform(spec.radius_min, spec.radius_max));
    volume += sphere_volume(out.final_radius.back());
  }
  const double scale = std::cbrt(solid / volume);
  for (auto& r : out.final_radius) r *= scale;

  // 2. Random non-overlapping positions at the reduced radii, largest first
  // (the standard trick of sequential random packing: small ones fill the gaps).
  std::vector<std::uint32_t> by_size(out.final_radius.size());
  for (std::uint32_t k = 0; k < by_size.size(); ++k) by_size[k] = k;
  std::stable_sort(by_size.begin(), by_size.end(), [&](auto a, auto b) { return out.final_radius[a] > out.final_radius[b]; });
  const double r_start_max = out.final_radius[by_size.front()] / spec.multiplier;
  const PeriodicSpace space(cell);
  PlacementGrid grid(cell, 2.0 * r_start_max);
  out.spheres.assign(out.final_radius.size(), {});
  constexpr int max_attempts = 100000;
  for (const auto k : by_size) {
    work_progress::advance();  // one sphere placed: up to max_attempts tries each, millions of spheres in a large REV
    const double r = out.final_radius[k] / spec.multiplier;
    bool placed = false;
    for (int attempt = 0; attempt < max_attempts && !placed; ++attempt) {
      Vec3 x;
      const auto coordinate = [&](std::size_t a, double lo, double hi) {
        return cell.periodic[a] ? random.uniform(lo, hi) : random.uniform(lo + r, hi - r);
      };
      x.x = coordinate(0, cell.lo.x, cell.hi.x);
      x.y = coordinate(1, cell.lo.y, cell.hi.y);
      x.z = coordinate(2, cell.lo.z, cell.hi.z);
      if (inside && !inside({x, r})) continue;
      bool free = true;
      grid.for_each_near(x, [&](std::uint32_t other) {
        const double reach = r + out.spheres[other].radius;
        free = free && norm2(space.branch(x, out.spheres[other].centre)) >= reach * reach;
      });
      if (!free) continue;
      out.spheres[k] = {x, r};
      grid.add(k, x);
      placed = true;
    }
    if (!placed)
      throw UserError("radius expansion: could not place " + std::to_string(out.final_radius.size()) +
                      " spheres without overlap at their reduced radii; raise the multiplier or the target porosity");
  }
  return out;
}

}  // namespace

ExpansionPacking place_for_radius_expansion(const RadiusExpansionSpec& spec, const PeriodicCell& cell) {
  return place(spec, cell, cell.volume(), nullptr);
}

ExpansionPacking place_for_radius_expansion(const RadiusExpansionSpec& spec, const BedRegion& region) {
  const auto [lo, hi] = region_bounds(region);
  const PeriodicCell bounds{.lo = lo, .hi = hi, .periodic = {false, false, false}, .strain_rate = {}};
  const double volume = region.shape == BedRegion::Shape::box ? bounds.volume() : std::numbers::pi * region.radius * region.radius * (hi.z - lo.z);
  return place(spec, bounds, volume, [&](const GeneratedSphere& s) { return clearance(s, region) >= 0.0; });
}

ExpansionReport expand_radii(Simulation& sim, std::span<const double> final_radius, const RadiusExpansionSpec& spec, double fraction_of_critical,
                             double volume) {
  ExpansionReport report;
  for (int stage = 1; stage <= spec.stages; ++stage) {
    ParticleStore& p = sim.particles_for_edit();
    for (std::size_t i = 0; i < p.size(); ++i) p.set_radius(i, stage_radius(final_radius[std::size_t(p.id[i])], spec.multiplier, stage, spec.stages));
    if (stage == spec.stages) report.porosity_geometric = 1.0 - sphere_volume_sum(p) / volume;
    const double dt = fraction_of_critical * sim.critical_timestep();
    for (std::int64_t s = 0; s < spec.relax_steps; ++s) sim.step(dt);
    report.steps += spec.relax_steps;
  }
  report.porosity_relaxed = 1.0 - sphere_volume_sum(sim.particles()) / volume;
  return report;
}

}  // namespace dfc::dem
