#include "dfc/dem/rcb_decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace dfc::dem {

namespace {
double component(const Vec3& x, int axis) noexcept { return axis == 0 ? x.x : axis == 1 ? x.y : x.z; }
void set_component(Vec3& x, int axis, double v) noexcept { (axis == 0 ? x.x : axis == 1 ? x.y : x.z) = v; }
}  // namespace

double SpaceBox::distance(const Vec3& x) const noexcept {
  const auto gap = [](double v, double low, double high) { return std::max({low - v, 0.0, v - high}); };
  const Vec3 d{gap(x.x, lo.x, hi.x), gap(x.y, lo.y, hi.y), gap(x.z, lo.z, hi.z)};
  return std::sqrt(norm2(d));
}

RcbDecomposition::RcbDecomposition(std::span<const Vec3> points, std::span<const double> weights, int parts) {
  if (parts < 1) throw std::invalid_argument("a decomposition needs at least one part");
  if (weights.size() != points.size()) throw std::invalid_argument("one weight per point");
  boxes_.resize(std::size_t(parts));
  std::vector<std::size_t> index(points.size());
  std::iota(index.begin(), index.end(), std::size_t{0});
  constexpr double inf = std::numeric_limits<double>::infinity();
  split(index, 0, index.size(), points, weights, 0, parts, SpaceBox{{-inf, -inf, -inf}, {inf, inf, inf}});
}

int RcbDecomposition::split(std::vector<std::size_t>& index, std::size_t begin, std::size_t end, std::span<const Vec3> points,
                            std::span<const double> weights, int first_part, int parts, SpaceBox box) {
  const int node = int(nodes_.size());
  nodes_.emplace_back();
  if (parts == 1) {
    nodes_[std::size_t(node)].part = first_part;
    boxes_[std::size_t(first_part)] = box;
    return node;
  }
  // The longest edge of the points' bounding box (the lowest axis of equal ones).
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (std::size_t k = begin; k < end; ++k) {
    const Vec3& x = points[index[k]];
    lo = {std::min(lo.x, x.x), std::min(lo.y, x.y), std::min(lo.z, x.z)};
    hi = {std::max(hi.x, x.x), std::max(hi.y, x.y), std::max(hi.z, x.z)};
  }
  int axis = 0;
  if (end > begin) {
    const Vec3 e = hi - lo;
    if (e.y > component(e, axis)) axis = 1;
    if (e.z > component(e, axis)) axis = 2;
  }
  const auto first = index.begin() + std::ptrdiff_t(begin), last = index.begin() + std::ptrdiff_t(end);
  // Ties by index: the order, and so the cut, is the same on every process.
  std::sort(first, last, [&](std::size_t a, std::size_t b) {
    const double ca = component(points[a], axis), cb = component(points[b], axis);
    return ca < cb || (ca == cb && a < b);
  });
  const int parts_below = parts / 2;
  double total = 0.0;
  for (std::size_t k = begin; k < end; ++k) total += weights[index[k]];
  const double target = total * double(parts_below) / double(parts);
  double at = 0.0;
  if (end - begin >= 2) {
    // The first point whose cumulative weight before it reaches the target.
    std::size_t k = begin + 1;
    double before = weights[index[begin]];
    while (k + 1 < end && before < target) before += weights[index[k++]];
    at = 0.5 * (component(points[index[k - 1]], axis) + component(points[index[k]], axis));
  } else if (end - begin == 1) {
    at = component(points[index[begin]], axis);  // the point goes above
  } else {
    // No points: cut the box in the middle (or at its one finite face).
    const double l = component(box.lo, axis), h = component(box.hi, axis);
    at = std::isfinite(l) && std::isfinite(h) ? 0.5 * (l + h) : std::isfinite(l) ? l : std::isfinite(h) ? h : 0.0;
  }
  // The points below the cut are those the owner() test puts there.
  const auto middle = std::partition_point(first, last, [&](std::size_t a) { return component(points[a], axis) < at; });
  const auto split_at = std::size_t(middle - index.begin());
  SpaceBox below = box, above = box;
  set_component(below.hi, axis, at);
  set_component(above.lo, axis, at);
  const int low_child = split(index, begin, split_at, points, weights, first_part, parts_below, below);
  const int high_child = split(index, split_at, end, points, weights, first_part + parts_below, parts - parts_below, above);
  Cut& cut = nodes_[std::size_t(node)];
  cut.axis = axis;
  cut.at = at;
  cut.below = low_child;
  cut.above = high_child;
  return node;
}

int RcbDecomposition::owner(const Vec3& x) const noexcept {
  int node = 0;
  while (nodes_[std::size_t(node)].axis >= 0) {
    const Cut& cut = nodes_[std::size_t(node)];
    node = component(x, cut.axis) < cut.at ? cut.below : cut.above;
  }
  return nodes_[std::size_t(node)].part;
}

}  // namespace dfc::dem
