#include "dfc/continuum/containing_triangles.hpp"

#include <algorithm>
#include <limits>

namespace dfc::continuum {

std::array<double, 3> barycentric_coordinates(const Point& p, const Point& a, const Point& b, const Point& c) {
  const auto cross = [](const Point& u, const Point& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double area = cross(b - a, c - a);
  return {cross(b - p, c - p) / area, cross(c - p, a - p) / area, cross(a - p, b - p) / area};
}

std::vector<Index> containing_triangles(std::span<const Point> nodes, std::span<const Triangle> triangles,
                                        std::span<const Point> points) {
  std::vector<Index> found;
  found.reserve(points.size());
  for (const Point& p : points) {
    Index most_inside = 0;
    double most_inside_value = -std::numeric_limits<double>::infinity();
    Index nearest = 0;
    double nearest_distance = std::numeric_limits<double>::infinity();
    for (Index t = 0; t < triangles.size(); ++t) {
      const Point& a = nodes[triangles[t][0]];
      const Point& b = nodes[triangles[t][1]];
      const Point& c = nodes[triangles[t][2]];
      const std::array<double, 3> weights = barycentric_coordinates(p, a, b, c);
      const double inside = std::min({weights[0], weights[1], weights[2]});
      if (inside > most_inside_value) most_inside_value = inside, most_inside = t;
      const double distance = (p - (a + b + c) / 3.0).squaredNorm();
      if (distance < nearest_distance) nearest_distance = distance, nearest = t;
    }
    // A point on an edge shared by two triangles is inside both to round-off; either is right.
    found.push_back(most_inside_value >= -1e-12 ? most_inside : nearest);
  }
  return found;
}

}  // namespace dfc::continuum
