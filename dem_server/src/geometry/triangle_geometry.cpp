#include "dfc/dem/triangle_geometry.hpp"

namespace dfc::dem {

FeatureVertices feature_vertices(TriangleFeature feature) noexcept {
  switch (feature) {
    case TriangleFeature::face: return {{0, 1, 2}, 3};
    case TriangleFeature::edge_ab: return {{0, 1, 0}, 2};
    case TriangleFeature::edge_bc: return {{1, 2, 0}, 2};
    case TriangleFeature::edge_ca: return {{2, 0, 0}, 2};
    case TriangleFeature::vertex_a: return {{0, 0, 0}, 1};
    case TriangleFeature::vertex_b: return {{1, 0, 0}, 1};
    case TriangleFeature::vertex_c: return {{2, 0, 0}, 1};
  }
  return {};
}

namespace {
ClosestPoint make(const Vec3& a, const Vec3& b, const Vec3& c, double wa, double wb, double wc, TriangleFeature feature) noexcept {
  // The point is formed from the weights themselves so that sum_k w_k x_k is
  // the contact point to rounding: the vertex forces w_k F then carry the
  // contact's moment exactly (wall_contacts.hpp).
  return {wa * a + wb * b + wc * c, {wa, wb, wc}, feature};
}
}  // namespace

ClosestPoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) noexcept {
  // Ericson (2005) §5.1.5, ClosestPtPointTriangle: test the vertex regions,
  // then the edge regions, else the projection lies inside the face.
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 ap = p - a;
  const double d1 = dot(ab, ap);
  const double d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return make(a, b, c, 1.0, 0.0, 0.0, TriangleFeature::vertex_a);

  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp);
  const double d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return make(a, b, c, 0.0, 1.0, 0.0, TriangleFeature::vertex_b);

  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return make(a, b, c, 1.0 - v, v, 0.0, TriangleFeature::edge_ab);
  }

  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp);
  const double d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return make(a, b, c, 0.0, 0.0, 1.0, TriangleFeature::vertex_c);

  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return make(a, b, c, 1.0 - w, 0.0, w, TriangleFeature::edge_ca);
  }

  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return make(a, b, c, 0.0, 1.0 - w, w, TriangleFeature::edge_bc);
  }

  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {  // degenerate triangle whose regions all failed: nearest vertex
    const double da = norm2(p - a), db = norm2(p - b), dc = norm2(p - c);
    if (da <= db && da <= dc) return make(a, b, c, 1.0, 0.0, 0.0, TriangleFeature::vertex_a);
    if (db <= dc) return make(a, b, c, 0.0, 1.0, 0.0, TriangleFeature::vertex_b);
    return make(a, b, c, 0.0, 0.0, 1.0, TriangleFeature::vertex_c);
  }
  const double v = vb / sum;
  const double w = vc / sum;
  return make(a, b, c, 1.0 - v - w, v, w, TriangleFeature::face);
}

double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) noexcept {
  return norm(p - closest_point_on_triangle(p, a, b, c).point);
}

Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c) noexcept {
  const Vec3 n = cross(b - a, c - a);
  const double len = norm(n);
  return len > 0.0 ? (1.0 / len) * n : Vec3{};
}

}  // namespace dfc::dem
