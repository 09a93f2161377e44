#include "dfc/dem/ucs_platens.hpp"

#include "dfc/common/errors.hpp"

namespace dfc::dem {

Vec3 vertex_centroid(std::span<const Vec3> vertices) {
  Vec3 sum;
  for (const auto& v : vertices) sum += v;
  return vertices.empty() ? sum : (1.0 / double(vertices.size())) * sum;
}

PlatenAxis platen_axis(std::span<const Vec3> top_vertices, std::span<const Vec3> bottom_vertices) {
  const Vec3 d = vertex_centroid(top_vertices) - vertex_centroid(bottom_vertices);
  const double h = norm(d);
  if (!(h > 0.0)) throw UserError("the two UCS platens have the same centroid; they must face each other across the sample");
  return {(1.0 / h) * d, h};
}

double platen_separation(const PlatenAxis& a, std::span<const Vec3> top_vertices, std::span<const Vec3> bottom_vertices) {
  return dot(vertex_centroid(top_vertices) - vertex_centroid(bottom_vertices), a.axis);
}

double axial_strain(const PlatenAxis& a, double separation) noexcept { return (a.initial_height - separation) / a.initial_height; }

double axial_stress(const PlatenAxis& a, const Vec3& force_on_top, const Vec3& force_on_bottom, double area) noexcept {
  return dot(force_on_top - force_on_bottom, a.axis) / (2.0 * area);
}

}  // namespace dfc::dem
