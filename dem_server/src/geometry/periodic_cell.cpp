#include "dfc/dem/periodic_cell.hpp"

#include <cstdint>
#include <limits>

#include "dfc/dem/parallel.hpp"

namespace dfc::dem {

namespace {
/// Scalar access to the three components (Vec3 is a plain aggregate).
double& component(Vec3& v, int a) noexcept { return a == 0 ? v.x : a == 1 ? v.y : v.z; }
double component(const Vec3& v, int a) noexcept { return a == 0 ? v.x : a == 1 ? v.y : v.z; }
}  // namespace

Vec3 PeriodicCell::wrap(const Vec3& x) const noexcept {
  Vec3 out = x;
  for (int a = 0; a < 3; ++a) {
    if (!periodic[std::size_t(a)]) continue;
    const double l = component(hi, a) - component(lo, a);
    double& c = component(out, a);
    c -= l * std::floor((c - component(lo, a)) / l);
    // floor can leave c == hi by round-off of a value just below lo.
    if (c >= component(hi, a)) c = component(lo, a);
  }
  return out;
}

Vec3 PeriodicCell::minimum_image(const Vec3& d) const noexcept { return PeriodicSpace(*this).branch(Vec3{}, d); }

void PeriodicCell::deform(double dt, std::span<Vec3> positions, std::span<Vec3> references, int threads) noexcept {
  const Vec3 c = centre();
  const Vec3 f{1.0 + strain_rate.x * dt, 1.0 + strain_rate.y * dt, 1.0 + strain_rate.z * dt};
  const auto stretch = [&](Vec3& x) { x = {c.x + f.x * (x.x - c.x), c.y + f.y * (x.y - c.y), c.z + f.z * (x.z - c.z)}; };
  // Every point on its own: the same bits for any thread count. (Serial, this
  // loop was 3 % of a two-thread step of the peer benchmark, idling the other thread.)
  const auto n = std::int64_t(positions.size());
#pragma omp parallel for schedule(static) num_threads(threads) if(n >= min_parallel_items)
  for (std::int64_t i = 0; i < n; ++i) {
    stretch(positions[std::size_t(i)]);
    if (std::size_t(i) < references.size()) stretch(references[std::size_t(i)]);
  }
  for (std::size_t i = positions.size(); i < references.size(); ++i) stretch(references[i]);
  stretch(lo);
  stretch(hi);
}

namespace {
constexpr double open_axis = std::numeric_limits<double>::infinity();
}  // namespace

PeriodicSpace::PeriodicSpace() : half_length{open_axis, open_axis, open_axis} {}

PeriodicSpace::PeriodicSpace(const PeriodicCell& cell) noexcept : length(cell.length()), strain_rate(cell.strain_rate) {
  half_length = {cell.periodic[0] ? 0.5 * length.x : open_axis, cell.periodic[1] ? 0.5 * length.y : open_axis,
                 cell.periodic[2] ? 0.5 * length.z : open_axis};
}

}  // namespace dfc::dem
