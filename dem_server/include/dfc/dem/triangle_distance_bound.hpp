#pragma once
// A cheap lower bound of the distance from a point to a triangle, to cull the
// candidates of a facet before the exact (closest-point) distance decides.
//
// A triangle lies in its plane and, within that plane, on the inner side of
// each of its edges: it is inside four half-spaces (the plane's two sides
// count as one slab |(p - a)·n| <= 0, and the three half-spaces bounded by the
// planes through an edge perpendicular to the triangle). The distance from p
// to the triangle is at least p's distance to each of these sets, hence at
// least their maximum: |(p - a)·n| and max(0, (p - v_i)·m_i) with m_i the
// in-plane outward normal of edge i. Each is one dot product, against the
// closest point's six and a square root.
#include <array>

#include "dfc/dem/vec3.hpp"

namespace dfc::dem {

class TriangleDistanceBound {
 public:
  /// The bound of triangle (a, b, c); a degenerate triangle (zero area, or a
  /// sliver: twice its area below 1e-6 of its longest edge squared) gets no
  /// half-spaces, so nothing is ever culled against it.
  TriangleDistanceBound(const Vec3& a, const Vec3& b, const Vec3& c) noexcept;

  /// A lower bound of distance_to_triangle(p, a, b, c) (exact arithmetic).
  [[nodiscard]] double lower_bound(const Vec3& p) const noexcept;

  /// True only where the triangle is certainly farther than `reach` from p,
  /// so that distance_to_triangle(p, a, b, c) < reach, evaluated in floating
  /// point, is false too. Both sides are computed from the same coordinates
  /// with a few roundings each: their errors are a few ulps of |p - a| (about
  /// 1e-16 |p - a|); the margin 1e-9 (reach + |p - a|_1) exceeds that by six
  /// orders of magnitude and culls nothing that matters (1e-13 m in a model
  /// 0.1 m across).
  [[nodiscard]] bool certainly_beyond(const Vec3& p, double reach) const noexcept;

 private:
  Vec3 origin_;                     // vertex a
  Vec3 normal_;                     // unit normal; zero when degenerate
  std::array<Vec3, 3> edge_point_;  // a point of each edge
  std::array<Vec3, 3> edge_out_;    // unit in-plane outward normal of each edge
  bool degenerate_ = true;
};

}  // namespace dfc::dem
