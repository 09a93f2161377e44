#include "dfc/dem/bed_generator.hpp"

#include <cmath>

#include "dfc/common/errors.hpp"
#include "dfc/dem/portable_random.hpp"

namespace dfc::dem {

std::vector<GeneratedSphere> generate_lattice_bed(const LatticeBedSpec& spec) {
  if (!(spec.radius_min > 0.0) || spec.radius_max < spec.radius_min)
    throw UserError("the bed generator needs 0 < radius_min <= radius_max");
  if (!(spec.spacing_factor >= 1.0)) throw UserError("the bed generator's spacing factor must be at least 1");
  const double pitch = 2.0 * spec.radius_max * spec.spacing_factor;
  const double half = 0.5 * pitch;
  const BedRegion& r = spec.region;
  const bool box = r.shape == BedRegion::Shape::box;
  // Lattice sites whose whole cell lies inside the region.
  const Vec3 lo = box ? r.min : Vec3{r.axis_x - r.radius, r.axis_y - r.radius, r.z_min};
  const Vec3 hi = box ? r.max : Vec3{r.axis_x + r.radius, r.axis_y + r.radius, r.z_max};
  const auto count = [&](double extent) { return extent >= pitch ? std::int64_t(std::floor(extent / pitch + 1e-9)) : std::int64_t{0}; };
  const std::int64_t nx = count(hi.x - lo.x), ny = count(hi.y - lo.y), nz = count(hi.z - lo.z);
  if (double(nx) * double(ny) * double(nz) > 5e7) throw UserError("the bed generator would create more than 5e7 particles; check the region and radii");

  PortableRandom random(spec.seed);
  std::vector<GeneratedSphere> out;
  for (std::int64_t k = 0; k < nz; ++k)
    for (std::int64_t j = 0; j < ny; ++j)
      for (std::int64_t i = 0; i < nx; ++i) {
        const Vec3 site{lo.x + half + double(i) * pitch, lo.y + half + double(j) * pitch, lo.z + half + double(k) * pitch};
        // In a cylinder the jitter may point diagonally: keep the whole jitter square inside.
        if (!box && std::hypot(site.x - r.axis_x, site.y - r.axis_y) > r.radius - std::sqrt(2.0) * half) continue;
        const double radius = random.uniform(spec.radius_min, spec.radius_max);
        const double jitter = half - radius;
        const Vec3 offset{random.uniform(-jitter, jitter), random.uniform(-jitter, jitter), random.uniform(-jitter, jitter)};
        out.push_back({site + offset, radius});
      }
  return out;
}

}  // namespace dfc::dem
