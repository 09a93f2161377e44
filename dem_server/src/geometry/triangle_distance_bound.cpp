#include "dfc/dem/triangle_distance_bound.hpp"

#include <algorithm>
#include <cmath>

#include "dfc/dem/triangle_geometry.hpp"

namespace dfc::dem {

TriangleDistanceBound::TriangleDistanceBound(const Vec3& a, const Vec3& b, const Vec3& c) noexcept
    : origin_(a), normal_(triangle_normal(a, b, c)) {
  // A sliver's normal is the direction of a cross product of nearly parallel
  // edges, whose rounding error is eps / (2 area / longest edge^2): below
  // 1e-6 that could exceed the margin of certainly_beyond, so a sliver culls
  // nothing (mesh facets are far from it: a pile's shaft facet has 0.017).
  const double longest2 = std::max({norm2(b - a), norm2(c - b), norm2(a - c)});
  degenerate_ = normal_ == Vec3{} || !(norm(cross(b - a, c - a)) > 1e-6 * longest2);
  if (degenerate_) return;
  const std::array<Vec3, 3> from{a, b, c};
  const std::array<Vec3, 3> to{b, c, a};
  for (std::size_t i = 0; i < 3; ++i) {
    // (to - from) x n points away from the triangle for a counter-clockwise
    // (a, b, c) about n = (b - a) x (c - a) / |...|.
    const Vec3 out = cross(to[i] - from[i], normal_);
    const double length = norm(out);
    edge_point_[i] = from[i];
    edge_out_[i] = length > 0.0 ? (1.0 / length) * out : Vec3{};
  }
}

double TriangleDistanceBound::lower_bound(const Vec3& p) const noexcept {
  if (degenerate_) return 0.0;
  double bound = std::abs(dot(p - origin_, normal_));
  for (std::size_t i = 0; i < 3; ++i) bound = std::max(bound, dot(p - edge_point_[i], edge_out_[i]));
  return bound;
}

bool TriangleDistanceBound::certainly_beyond(const Vec3& p, double reach) const noexcept {
  if (degenerate_) return false;
  const Vec3 d = p - origin_;
  const double margin = 1e-9 * (reach + std::abs(d.x) + std::abs(d.y) + std::abs(d.z));
  return lower_bound(p) > reach + margin;
}

}  // namespace dfc::dem
