#pragma once
// Closest point of a triangle to a point (sphere centre), with the feature of
// the triangle it lies on and its barycentric weights. The sphere–facet
// contact (wall_contacts) and the vertex force distribution are built on it.
#include <array>
#include <cstdint>

#include "dfc/dem/vec3.hpp"

namespace dfc::dem {

/// Which part of a triangle (a, b, c) the closest point lies on.
enum class TriangleFeature : std::uint8_t {
  face,      ///< interior (the sphere centre projects inside the triangle)
  edge_ab,
  edge_bc,
  edge_ca,
  vertex_a,
  vertex_b,
  vertex_c,
};

/// Local vertex indices (0..2) that span `feature`; count = 3, 2 or 1.
struct FeatureVertices {
  std::array<std::uint8_t, 3> local{};
  std::uint8_t count = 0;
};
[[nodiscard]] FeatureVertices feature_vertices(TriangleFeature feature) noexcept;

struct ClosestPoint {
  Vec3 point;                     ///< = w[0] a + w[1] b + w[2] c
  std::array<double, 3> weights;  ///< barycentric weights, >= 0, sum 1 (to rounding)
  TriangleFeature feature = TriangleFeature::face;
};

/// Closest point of triangle (a, b, c) to p: Voronoi-region test of
/// Ericson, Real-Time Collision Detection (2005), §5.1.5. Degenerate
/// (zero-area) triangles fall back to an edge or vertex.
[[nodiscard]] ClosestPoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) noexcept;

/// Distance from p to the triangle (a, b, c).
[[nodiscard]] double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) noexcept;

/// Unit normal (b - a) x (c - a) / |...|; zero for a degenerate triangle.
[[nodiscard]] Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c) noexcept;

}  // namespace dfc::dem
