#pragma once
// Weighted recursive coordinate bisection (Berger & Bokhari, IEEE Trans.
// Computers 36(5), 1987, doi:10.1109/TC.1987.1676942): space cut into
// `parts` boxes, each holding about the same weight of points. A decomposed
// DEM run (distributed_simulation.hpp) gives each process one box; a point's
// weight is its share of the work (a graded body holds ~12x the spheres per
// volume in its fine zone, so boxes of equal weight are far from equal size).
//
// Each cut halves the parts (⌊p/2⌋ and ⌈p/2⌉, weights in that ratio) across
// the longest edge of the points' bounding box, half-way between the last
// point of the lower side and the first of the upper one. The boxes tile all
// of space (the outer faces are at infinity), so every position has exactly
// one owner however far a particle moves before the next decomposition. The
// result depends only on the points and weights in the order given: every
// process that computes it from the same gathered arrays gets the same boxes.
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "dfc/dem/vec3.hpp"

namespace dfc::dem {

/// A box [lo, hi) of space (faces may be at +-infinity).
struct SpaceBox {
  Vec3 lo, hi;
  [[nodiscard]] bool contains(const Vec3& x) const noexcept {
    return x.x >= lo.x && x.x < hi.x && x.y >= lo.y && x.y < hi.y && x.z >= lo.z && x.z < hi.z;
  }
  /// m, the distance from x to the box (0 inside).
  [[nodiscard]] double distance(const Vec3& x) const noexcept;
};

class RcbDecomposition {
 public:
  /// Cuts space into `parts` (>= 1) boxes of about equal weight of the points.
  RcbDecomposition(std::span<const Vec3> points, std::span<const double> weights, int parts);
  [[nodiscard]] int parts() const noexcept { return int(boxes_.size()); }
  [[nodiscard]] const SpaceBox& box(int part) const { return boxes_.at(std::size_t(part)); }
  /// The part whose box holds x (a walk down the cuts: log2(parts) tests).
  [[nodiscard]] int owner(const Vec3& x) const noexcept;

 private:
  struct Cut {
    int axis = -1;  ///< -1: a leaf, `part` is its part
    double at = 0.0;
    int part = 0;
    int below = -1, above = -1;  ///< child nodes
  };
  int split(std::vector<std::size_t>& index, std::size_t begin, std::size_t end, std::span<const Vec3> points, std::span<const double> weights,
            int first_part, int parts, SpaceBox box);
  std::vector<Cut> nodes_;
  std::vector<SpaceBox> boxes_;
};

}  // namespace dfc::dem
