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
  const bool fcc = spec.arrangement == LatticeArrangement::fcc;
  // Close-packed layers (fcc, ABC stacking): rows sqrt(3)/2 a apart, layers
  // sqrt(2/3) a apart, each row shifted a/2 and each layer shifted by a/2 in x
  // and a/(2 sqrt 3) in y.
  const double dx = pitch;
  const double dy = fcc ? pitch * std::sqrt(3.0) / 2.0 : pitch;
  const double dz = fcc ? pitch * std::sqrt(2.0 / 3.0) : pitch;
  const double jitter_scale = fcc ? 1.0 / std::sqrt(3.0) : 1.0;
  const BedRegion& r = spec.region;
  const bool box = r.shape == BedRegion::Shape::box;
  const Vec3 lo = box ? r.min : Vec3{r.axis_x - r.radius, r.axis_y - r.radius, r.z_min};
  const Vec3 hi = box ? r.max : Vec3{r.axis_x + r.radius, r.axis_y + r.radius, r.z_max};
  // Sites count along an axis: the first at lo + a/2, the last at most hi - a/2
  // (plus the row/layer shift of at most a/2 + a/(2 sqrt 3) on the fcc lattice).
  const double margin_x = fcc ? half : 0.0;
  const double margin_y = fcc ? 2.0 * half / std::sqrt(3.0) : 0.0;
  const auto count = [&](double extent, double step, double margin) {
    const double usable = extent - pitch - margin;
    return usable >= 0.0 ? std::int64_t(std::floor(usable / step + 1e-9)) + 1 : std::int64_t{0};
  };
  const std::int64_t nx = count(hi.x - lo.x, dx, margin_x), ny = count(hi.y - lo.y, dy, margin_y), nz = count(hi.z - lo.z, dz, 0.0);
  if (double(nx) * double(ny) * double(nz) > 5e7) throw UserError("the bed generator would create more than 5e7 particles; check the region and radii");

  PortableRandom random(spec.seed);
  std::vector<GeneratedSphere> out;
  for (std::int64_t k = 0; k < nz; ++k)
    for (std::int64_t j = 0; j < ny; ++j)
      for (std::int64_t i = 0; i < nx; ++i) {
        // Layer k of type A, B, C (k mod 3) sits over the A, B, C hollows of the
        // triangular lattice: offsets (0, 0), (a/2, a/(2 sqrt 3)), (a, a/sqrt 3) ≡ (0, a/sqrt 3).
        const std::int64_t layer_type = k % 3;
        const bool shifted = fcc && ((j % 2 == 1) != (layer_type == 1));
        const double shift_x = shifted ? half : 0.0;
        const double shift_y = fcc ? half / std::sqrt(3.0) * double(layer_type) : 0.0;
        Vec3 site{lo.x + half + double(i) * dx + shift_x, lo.y + half + double(j) * dy + shift_y, lo.z + half + double(k) * dz};
        // In a cylinder the jitter may point diagonally: keep the whole jitter square inside.
        if (!box && std::hypot(site.x - r.axis_x, site.y - r.axis_y) > r.radius - std::sqrt(2.0) * half) continue;
        const double radius = random.uniform(spec.radius_min, spec.radius_max);
        const double jitter = (half - radius) * jitter_scale;
        const Vec3 offset{random.uniform(-jitter, jitter), random.uniform(-jitter, jitter), random.uniform(-jitter, jitter)};
        out.push_back({site + offset, radius});
      }
  return out;
}

}  // namespace dfc::dem
