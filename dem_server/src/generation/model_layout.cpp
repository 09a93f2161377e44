#include "dfc/dem/model_layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dfc/common/errors.hpp"
#include "dfc/dem/region_config.hpp"
#include "dfc/dem/ucs_platens.hpp"
#include "dfc/dem/wall_builders.hpp"

namespace dfc::dem {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

/// Bounding box of the spheres, for default wall sizes.
std::pair<Vec3, Vec3> bounding_box(std::span<const GeneratedSphere> spheres) {
  Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  for (const auto& s : spheres) {
    const Vec3 r{s.radius, s.radius, s.radius};
    const Vec3 a = s.centre - r, b = s.centre + r;
    lo = {std::min(lo.x, a.x), std::min(lo.y, a.y), std::min(lo.z, a.z)};
    hi = {std::max(hi.x, b.x), std::max(hi.y, b.y), std::max(hi.z, b.z)};
  }
  return {lo, hi};
}

/// Stage 1: the generator's spheres before the walls (none for pcrm, none
/// yet for a radius expansion inside triaxial walls).
void place_spheres(const DemConfig& c, ModelLayout& layout) {
  const ParticleConfig& p = c.particles;
  if (p.generator == "lattice") {
    layout.spheres = generate_lattice_bed(p.lattice);
    if (layout.spheres.empty())
      throw ConfigError("particles.region", "no sphere fits: the region must be at least 2 radius_max_m x spacing_factor wide in every direction");
  } else if (p.generator == "list") {
    layout.spheres = p.listed;
  } else if (p.generator == "radius_expansion" && c.periodic) {
    try {
      ExpansionPacking packing = place_for_radius_expansion(p.expansion, c.periodic->cell);
      layout.spheres = std::move(packing.spheres);
      layout.final_radius = std::move(packing.final_radius);
    } catch (const UserError& e) {
      throw ConfigError("particles.multiplier", e.what());
    }
  }
  if (!c.periodic) return;
  // Every periodic edge must hold 2 (2 r_max + reach) with the final radii.
  double r_max = 0.0;
  if (p.generator == "radius_expansion")
    for (const double r : layout.final_radius) r_max = std::max(r_max, r);
  else
    for (const auto& s : layout.spheres) r_max = std::max(r_max, s.radius);
  const double skin = c.skin > 0.0 ? c.skin : 0.2 * r_max;
  check_periodic_width(*c.periodic, r_max, std::max(skin, c.contact.bond_gap()), "periodic.");
}

/// Stage 2: a plane without half_size_m covers the particles' bounding box
/// seen from its point, generously (the region's box for a generated body).
void size_walls(const DemConfig& c, ModelLayout& layout) {
  const auto box = c.particles.pcrm ? region_bounds(c.particles.pcrm->region) : bounding_box(layout.spheres);
  for (WallConfig& wall : layout.walls) {
    if (!wall.plane_to_size) continue;
    const Vec3 centre = 0.5 * (box.first + box.second);
    const double half_size = norm(centre - wall.plane_to_size->point) + norm(box.second - box.first);
    wall.mesh = make_plane_mesh(wall.plane_to_size->point, wall.plane_to_size->normal, half_size);
    wall.plane_to_size.reset();
  }
}

/// Stage 4: a radius expansion inside the six walls of a triaxial section:
/// the box their centroids bound (walls normal to x, y and z, checked by the
/// reader; each centroid is the lowest or highest of the six along its own
/// normal, the middle along the others) as a cell with no periodic axis, so
/// the placement keeps whole spheres inside it.
void place_in_walls(const DemConfig& c, ModelLayout& layout) {
  if (c.particles.generator != "radius_expansion" || c.periodic) return;
  PeriodicCell box{.lo = {inf, inf, inf}, .hi = {-inf, -inf, -inf}, .periodic = {false, false, false}, .strain_rate = {}};
  for (const auto& v : wall_box_vertices(layout.walls, c.triaxial->walls)) {
    const Vec3 x = vertex_centroid(v);
    box.lo = {std::min(box.lo.x, x.x), std::min(box.lo.y, x.y), std::min(box.lo.z, x.z)};
    box.hi = {std::max(box.hi.x, x.x), std::max(box.hi.y, x.y), std::max(box.hi.z, x.z)};
  }
  try {
    ExpansionPacking packing = place_for_radius_expansion(c.particles.expansion, box);
    layout.spheres = std::move(packing.spheres);
    layout.final_radius = std::move(packing.final_radius);
  } catch (const UserError& e) {
    throw ConfigError("particles.multiplier", e.what());
  }
}

}  // namespace

void seat_on_particles(WallConfig& high, WallConfig& low, std::span<const GeneratedSphere> spheres, const Vec3& axis) {
  double top = -inf, bottom = inf;
  for (const auto& s : spheres) {
    top = std::max(top, dot(s.centre, axis) + s.radius);
    bottom = std::min(bottom, dot(s.centre, axis) - s.radius);
  }
  const auto shift = [&](WallConfig& wall, double target) {
    const Vec3 delta = (target - dot(vertex_centroid(wall.mesh.vertices), axis)) * axis;
    for (auto& v : wall.mesh.vertices) v += delta;
  };
  shift(high, top);
  shift(low, bottom);
}

ModelLayout lay_out_model(const DemConfig& config, std::span<const std::unique_ptr<LoadingProtocol>> protocols) {
  ModelLayout layout;
  place_spheres(config, layout);
  layout.walls = config.walls;
  size_walls(config, layout);
  for (const auto& protocol : protocols) protocol->arrange(layout);
  place_in_walls(config, layout);
  return layout;
}

ModelLayout lay_out_model(const DemConfig& config) { return lay_out_model(config, make_loading_protocols(config)); }

}  // namespace dfc::dem
