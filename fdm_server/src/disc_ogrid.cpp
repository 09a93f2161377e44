#include "disc_ogrid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "dfc/common/errors.hpp"
#include "structured_mesh.hpp"

namespace dfc::fdm::detail {

Index disc_ring_zones(Index zones_around) {
  const double n = double(zones_around);
  const double mean_width = 0.5 * ((1.0 - kCoreHalfDiagonal) + 0.5);                // in R
  const double mean_edge = 0.5 * (4.0 / n + 2.0 * std::numbers::pi / n);           // in R: core R / m, circle 2π R / n
  return std::max<Index>(1, Index(std::lround(mean_width / mean_edge)));
}

void add_disc_ogrid(Mesh& mesh, Index zones_around, Index layers, const CircleNode& circle_node, const std::string& bottom_group,
                    const std::vector<std::string>& top_groups) {
  const Index nt = zones_around;
  if (nt < 4 || nt % 4 != 0) throw UserError("the O-grid of a solid disc needs zones_around to be a multiple of 4 (got " + std::to_string(nt) + ")");
  const Index m = nt / 4;
  const Index nc = disc_ring_zones(nt);
  const Vec3 first = mesh.points[circle_node(0, 0)];
  const double a = kCoreHalfDiagonal * std::hypot(first.x(), first.y());

  // Diamond perimeter point j (counter-clockwise from the corner (a, 0), m per
  // side, corners at j = 0, m, 2m, 3m), so that spoke j ends at circle node j.
  const std::array<Vec3, 5> corners = {Vec3(a, 0, 0), Vec3(0, a, 0), Vec3(-a, 0, 0), Vec3(0, -a, 0), Vec3(a, 0, 0)};
  const auto perimeter = [&](Index j) {
    const Index side = j / m;
    const double t = double(j % m) / double(m);
    return Vec3(corners[side] + t * (corners[side + 1] - corners[side]));
  };

  // Gridpoints: ring layers l = 0 .. nc-1 (l = nc is the circle), then the
  // diamond's interior (p, q = 1 .. m-1), level by level.
  const Index ring_base = mesh.points.size();
  const Index core_base = ring_base + nc * nt * (layers + 1);
  mesh.points.reserve(core_base + (m - 1) * (m - 1) * (layers + 1));
  for (Index k = 0; k <= layers; ++k)
    for (Index j = 0; j < nt; ++j) {
      const Vec3 circle = mesh.points[circle_node(j, k)];
      const Vec3 inner = perimeter(j) + Vec3(0.0, 0.0, circle.z());
      for (Index l = 0; l < nc; ++l) mesh.points.push_back(inner + (double(l) / double(nc)) * (circle - inner));
    }
  // Diamond lattice (p, q): x = a (u - v), y = a (u + v - 1) with u = p/m,
  // v = q/m, the affine map of the unit square onto the diamond with
  // (0,0) → (0,-a), (1,0) → (a,0), (0,1) → (-a,0); ∂x/∂u × ∂x/∂v = 2a² e_z > 0,
  // so (p, q, k) is right-handed like the annulus's (r, θ, z).
  for (Index k = 0; k <= layers; ++k) {
    const double z = mesh.points[circle_node(0, k)].z();
    for (Index q = 1; q < m; ++q)
      for (Index p = 1; p < m; ++p) {
        const double u = double(p) / double(m), v = double(q) / double(m);
        mesh.points.emplace_back(a * (u - v), a * (u + v - 1.0), z);
      }
  }

  const LatticeNodeIndex ring_node = [=](Index l, Index j, Index k) {
    const Index jj = j % nt;  // the ring closes on itself
    return l == nc ? circle_node(jj, k) : ring_base + l + nc * (jj + nt * k);
  };
  // The diamond's boundary nodes are ring layer 0 (see perimeter()).
  const LatticeNodeIndex core_node = [=](Index p, Index q, Index k) {
    Index j = 0;
    if (q == 0) j = (3 * m + p) % nt;  // S → E
    else if (p == m) j = q;            // E → N
    else if (q == m) j = 2 * m - p;    // N ← W
    else if (p == 0) j = 3 * m - q;    // S → W
    else return core_base + (p - 1) + (m - 1) * ((q - 1) + (m - 1) * k);
    return ring_node(0, j, k);
  };
  const std::array<Index, 3> ring_counts = {nc, nt, layers};
  const std::array<Index, 3> core_counts = {m, m, layers};
  add_lattice_zones(mesh, ring_counts, ring_node);
  add_lattice_zones(mesh, core_counts, core_node);
  add_lattice_face_group(mesh, bottom_group, ring_counts, ring_node, 2, 0);
  add_lattice_face_group(mesh, bottom_group, core_counts, core_node, 2, 0);
  for (const std::string& group : top_groups) {
    add_lattice_face_group(mesh, group, ring_counts, ring_node, 2, 1);
    add_lattice_face_group(mesh, group, core_counts, core_node, 2, 1);
  }
}

}  // namespace dfc::fdm::detail
