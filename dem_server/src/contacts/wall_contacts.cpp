#include "dfc/dem/wall_contacts.hpp"
#include "dfc/dem/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "dfc/dem/triangle_geometry.hpp"

namespace dfc::dem {

namespace {

int rank(TriangleFeature f) noexcept {
  if (f == TriangleFeature::face) return 0;
  return feature_vertices(f).count == 2 ? 1 : 2;
}

bool facet_contains(const Facet& facet, std::uint32_t vertex) noexcept {
  return facet[0] == vertex || facet[1] == vertex || facet[2] == vertex;
}

bool facets_share_a_vertex(const Facet& a, const Facet& b) noexcept {
  return facet_contains(b, a[0]) || facet_contains(b, a[1]) || facet_contains(b, a[2]);
}

bool row_is_clear(const double* row, std::size_t stride) noexcept {
  return std::all_of(row, row + stride, [](double v) { return v == 0.0; });
}

/// A contact that moved onto a neighbouring facet keeps its history (see
/// wall_contacts.hpp). In candidates [begin, end) of one particle: each
/// facet no longer selected whose row still holds a history (the force loop
/// clears it only after this) hands it to the newly selected facet (clear row)
/// that shares a vertex with it and whose contact point is nearest its own,
/// within `reach`; ties go to the lower index.
void carry_history_to_new_facets(const Wall& wall, WallContacts& contacts, std::span<const Vec3> points, std::size_t begin, std::size_t end,
                                 double reach) {
  for (std::size_t m = begin; m < end; ++m) {
    if (contacts.selected[m] != 0 || row_is_clear(contacts.row(m), contacts.stride)) continue;
    const Facet& old_facet = wall.facets[contacts.facet[m]];
    std::size_t heir = end;
    double nearest2 = reach * reach;
    for (std::size_t k = begin; k < end; ++k) {
      if (contacts.selected[k] == 0 || !row_is_clear(contacts.row(k), contacts.stride)) continue;
      if (!facets_share_a_vertex(old_facet, wall.facets[contacts.facet[k]])) continue;
      const double d2 = norm2(points[k] - points[m]);
      if (d2 < nearest2) {
        nearest2 = d2;
        heir = k;
      }
    }
    if (heir == end) continue;
    std::copy(contacts.row(m), contacts.row(m) + contacts.stride, contacts.row(heir));
    std::fill(contacts.row(m), contacts.row(m) + contacts.stride, 0.0);
  }
}

}  // namespace

void select_wall_contacts(const Wall& wall, const ParticleStore& particles, WallContacts& contacts, std::span<Vec3> points, int threads) {
  const auto groups = static_cast<std::int64_t>(contacts.group_count());
#pragma omp parallel for schedule(static) num_threads(threads) if(groups >= min_parallel_items)
  for (std::int64_t g = 0; g < groups; ++g) {
    const std::size_t begin = contacts.group_start[std::size_t(g)];
    const std::size_t end = contacts.group_start[std::size_t(g) + 1];
    const Vec3 centre = particles.position[contacts.particle[begin]];
    for (std::size_t k = begin; k < end; ++k) {
      const Facet& f = wall.facets[contacts.facet[k]];
      const ClosestPoint cp = closest_point_on_triangle(centre, wall.vertices[f[0]], wall.vertices[f[1]], wall.vertices[f[2]]);
      points[k] = cp.point;
      contacts.weights[k] = cp.weights;
      contacts.distance[k] = norm(centre - cp.point);
      contacts.feature[k] = static_cast<std::uint8_t>(cp.feature);
    }
    // Distances that differ by rounding only count as ties.
    const double tie = 1e-12 * particles.radius[contacts.particle[begin]];
    for (std::size_t k = begin; k < end; ++k) {
      const auto feature = static_cast<TriangleFeature>(contacts.feature[k]);
      contacts.selected[k] = 1;
      if (feature == TriangleFeature::face) continue;
      const Facet& own = wall.facets[contacts.facet[k]];
      const FeatureVertices local = feature_vertices(feature);
      for (std::size_t m = begin; m < end && contacts.selected[k] != 0; ++m) {
        if (m == k) continue;
        const Facet& other = wall.facets[contacts.facet[m]];
        bool contains = true;
        for (std::uint8_t v = 0; v < local.count; ++v) contains = contains && facet_contains(other, own[local.local[v]]);
        if (!contains) continue;
        const double dm = contacts.distance[m], dk = contacts.distance[k];
        const int rm = rank(static_cast<TriangleFeature>(contacts.feature[m])), rk = rank(feature);
        const bool better = dm < dk - tie || (std::abs(dm - dk) <= tie && (rm < rk || (rm == rk && m < k)));
        if (better) contacts.selected[k] = 0;
      }
    }
    if (contacts.stride > 0) carry_history_to_new_facets(wall, contacts, points, begin, end, particles.radius[contacts.particle[begin]]);
  }
}

}  // namespace dfc::dem
