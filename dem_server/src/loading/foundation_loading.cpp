#include "dfc/dem/foundation_loading.hpp"

#include <algorithm>

namespace dfc::dem {

Vec3 ramped_velocity(const Vec3& velocity, std::int64_t steps_moving, std::int64_t ramp_steps) {
  if (steps_moving >= ramp_steps) return velocity;
  return (double(steps_moving + 1) / double(ramp_steps)) * velocity;
}

bool pile_may_start(const PileStartRule& rule, std::int64_t step, std::int64_t start_step, double unbalanced_force_ratio) {
  return step >= start_step && unbalanced_force_ratio <= rule.unbalanced_force_ratio;
}

std::vector<std::size_t> pile_tip_facets(const Wall& pile, const Vec3& direction) {
  const double speed = norm(direction);
  const Vec3 d = speed > 0.0 ? (1.0 / speed) * direction : Vec3{0.0, 0.0, -1.0};
  std::vector<std::size_t> tip;
  for (std::size_t f = 0; f < pile.facets.size(); ++f) {
    const Facet& facet = pile.facets[f];
    const Vec3 a = pile.vertices[facet[0]], b = pile.vertices[facet[1]], c = pile.vertices[facet[2]];
    const Vec3 n = cross(b - a, c - a);
    const double length = norm(n);
    if (length > 0.0 && dot(n, d) >= (1.0 - 1e-6) * length) tip.push_back(f);
  }
  return tip;
}

std::vector<std::size_t> pile_inner_facets(const Wall& pile, double axis_x, double axis_y) {
  std::vector<std::size_t> inner;
  for (std::size_t f = 0; f < pile.facets.size(); ++f) {
    const Facet& facet = pile.facets[f];
    const Vec3 a = pile.vertices[facet[0]], b = pile.vertices[facet[1]], c = pile.vertices[facet[2]];
    const Vec3 n = cross(b - a, c - a);
    const Vec3 centroid = (1.0 / 3.0) * (a + b + c);
    if (n.x * (centroid.x - axis_x) + n.y * (centroid.y - axis_y) < 0.0) inner.push_back(f);
  }
  return inner;
}

std::vector<std::size_t> other_facets(const Wall& pile, std::span<const std::size_t> tip, std::span<const std::size_t> inner) {
  std::vector<std::size_t> rest;
  for (std::size_t f = 0; f < pile.facets.size(); ++f)
    if (!std::binary_search(tip.begin(), tip.end(), f) && !std::binary_search(inner.begin(), inner.end(), f)) rest.push_back(f);
  return rest;
}

Vec3 facets_force(const Wall& wall, std::span<const std::size_t> facets) {
  Vec3 sum;
  for (const std::size_t f : facets) sum += wall.facet_force[f];
  return sum;
}

}  // namespace dfc::dem
