#include "dfc/dem/particle_stress.hpp"

#include <cmath>
#include <numbers>

#include "dfc/dem/exact_sum.hpp"
#include "dfc/dem/region_config.hpp"

namespace dfc::dem {

namespace {

void add_moment(Stress6& s, const Vec3& f, const Vec3& r) {
  // -(f (x) r), symmetrised: compression positive.
  s[0] -= f.x * r.x;
  s[1] -= 0.5 * (f.x * r.y + f.y * r.x);
  s[2] -= 0.5 * (f.x * r.z + f.z * r.x);
  s[3] -= f.y * r.y;
  s[4] -= 0.5 * (f.y * r.z + f.z * r.y);
  s[5] -= f.z * r.z;
}

double sphere_volume(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }

}  // namespace

std::vector<Stress6> particle_stress(const Simulation& sim) {
  const ParticleStore& p = sim.particles();
  std::vector<Stress6> out(p.size(), Stress6{});
  if (sim.step_count() == 0 || !sim.contact_outputs_complete()) return out;
  const ContactOutputs& c = sim.contact_outputs();
  const PairContacts& pairs = sim.pair_contacts();
  if (c.force.size() < pairs.size()) return out;  // no force evaluation since the lists changed
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const Vec3& f = c.force[k];
    if (f == Vec3{}) continue;
    const std::uint32_t i = pairs.first[k], j = pairs.second[k];
    const Vec3 shift = c.shift.empty() ? Vec3{} : c.shift[k];  // periodic image of the second body
    add_moment(out[i], f, c.point[k] - p.position[i]);
    add_moment(out[j], -1.0 * f, c.point[k] - (p.position[j] + shift));
  }
  for (std::size_t w = 0; w < sim.walls().size(); ++w) {
    const WallContacts& wc = sim.wall_contacts(w);
    const std::size_t offset = sim.wall_output_offset(w);
    for (std::size_t k = 0; k < wc.size(); ++k) {
      const Vec3& f = c.force[offset + k];
      if (f == Vec3{}) continue;
      const std::uint32_t i = wc.particle[k];
      add_moment(out[i], f, c.point[offset + k] - p.position[i]);
    }
  }
  for (std::size_t i = 0; i < p.size(); ++i)
    for (double& v : out[i]) v /= sphere_volume(p.radius[i]);
  return out;
}

SliceProfile slice_profile(const Simulation& sim, const BedRegion& region, int slices, double margin) {
  return slice_profile(sim.particles().position, sim.particles().radius, particle_stress(sim), region, slices, margin);
}

SliceProfile slice_profile(std::span<const Vec3> position, std::span<const double> radius, std::span<const Stress6> stress,
                           const BedRegion& region, int slices, double margin) {
  BedRegion inner = region;
  if (region.shape == BedRegion::Shape::box) {
    inner.min = region.min + Vec3{margin, margin, 0.0};
    inner.max = region.max - Vec3{margin, margin, 0.0};
  } else {
    inner.radius = region.radius - margin;
  }
  const auto [lo, hi] = region_bounds(inner);
  const double height = (hi.z - lo.z) / double(slices);
  const double area = inner.shape == BedRegion::Shape::box ? (hi.x - lo.x) * (hi.y - lo.y) : std::numbers::pi * inner.radius * inner.radius;
  if (!(area > 0.0)) return {};
  // Per slice: the moments V_p sigma_p (zz, xx, yy) and the solid volume.
  std::vector<std::array<ExactSum, 4>> sums(static_cast<std::size_t>(slices));
  for (std::size_t i = 0; i < position.size(); ++i) {
    const Vec3& x = position[i];
    const double z = x.z;
    if (z < lo.z || z >= hi.z) continue;
    const bool inside = inner.shape == BedRegion::Shape::box ? (x.x >= lo.x && x.x < hi.x && x.y >= lo.y && x.y < hi.y)
                                                             : std::hypot(x.x - inner.axis_x, x.y - inner.axis_y) < inner.radius;
    if (!inside) continue;
    const auto s = std::size_t(std::min(double(slices - 1), std::floor((hi.z - z) / height)));  // slice 0 at the top
    const double v = sphere_volume(radius[i]);
    sums[s][0].add(v * stress[i][5]);
    sums[s][1].add(v * stress[i][0]);
    sums[s][2].add(v * stress[i][3]);
    sums[s][3].add(v);
  }
  SliceProfile out;
  const double volume = area * height;
  for (std::size_t s = 0; s < std::size_t(slices); ++s) {
    out.z.push_back(hi.z - (double(s) + 0.5) * height);
    out.sigma_v.push_back(sums[s][0].value() / volume);
    out.sigma_h.push_back(0.5 * (sums[s][1].value() + sums[s][2].value()) / volume);
    out.porosity.push_back(1.0 - sums[s][3].value() / volume);
  }
  return out;
}

}  // namespace dfc::dem
