// One octant of a spherical shell around a spherical cavity, as three
// structured patches. Patch k (k = 0, 1, 2 for the x, y, z axes) spans the
// quadrilateral A B C D of the octant's spherical triangle, with
//   A = e_k, B = (e_k + e_{k+1})/√2, C = (1,1,1)/√3, D = (e_k + e_{k+2})/√2,
// parametrised by (s, t) ∈ [0,1]² (bilinear in the flat quadrilateral, then
// projected onto the sphere). Lattice directions (r, s, t) are right-handed
// (for k = 0 they point along x, y, z), so the FLAC3D corner order gives
// positive tetrahedra. Patch k's edge s = 1 (B→C) is patch k+1's edge t = 1
// (its D→C); both are computed by the same expression, so their gridpoints
// coincide bit for bit and are merged by exact coordinates.
#include <cmath>
#include <map>

#include "dfc/common/errors.hpp"
#include "dfc/fdm/grading.hpp"
#include "dfc/fdm/mesh_generators.hpp"
#include "dfc/fdm/mesh_quality.hpp"
#include "structured_mesh.hpp"

namespace dfc::fdm {

namespace {

Vec3 lerp(const Vec3& x, const Vec3& y, double t) { return (1.0 - t) * x + t * y; }

// Unit direction of lattice node (a, b) of patch k with n zones per edge.
Vec3 patch_direction(int k, Index a, Index b, Index n) {
  const Vec3 e[3] = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  const Vec3& ek = e[k];
  const Vec3& ek1 = e[(k + 1) % 3];
  const Vec3& ek2 = e[(k + 2) % 3];
  const Vec3 corner_a = ek;
  const Vec3 corner_b = (ek + ek1) / std::sqrt(2.0);
  const Vec3 corner_c = Vec3::Ones() / std::sqrt(3.0);
  const Vec3 corner_d = (ek + ek2) / std::sqrt(2.0);
  const double s = double(a) / double(n);
  const double t = double(b) / double(n);
  Vec3 flat;
  if (a == n) {
    flat = lerp(corner_b, corner_c, t);  // shared with patch k+1 (its t = 1 edge)
  } else if (b == n) {
    flat = lerp(corner_d, corner_c, s);  // shared with patch k−1 (its s = 1 edge)
  } else {
    flat = lerp(lerp(corner_a, corner_b, s), lerp(corner_d, corner_c, s), t);
  }
  return flat.normalized();
}

}  // namespace

Mesh make_sphere_cavity_octant(const SphereCavityOctantSpec& spec) {
  if (!(spec.inner_radius > 0.0) || !(spec.outer_radius > spec.inner_radius))
    throw UserError("sphere_cavity_octant: need 0 < inner_radius < outer_radius");
  if (spec.zones_radial < 1 || spec.zones_around < 1) throw UserError("sphere_cavity_octant: need zones_radial >= 1 and zones_around >= 1");
  if (!(spec.grading_ratio > 0.0)) throw UserError("sphere_cavity_octant: grading_ratio must be > 0");

  const Index nr = spec.zones_radial;
  const Index n = spec.zones_around;
  const std::vector<double> radii = geometric_spacing(spec.inner_radius, spec.outer_radius, nr, spec.grading_ratio);

  Mesh mesh;
  std::map<std::array<double, 3>, Index> index_of;  // merges the shared patch edges
  std::array<std::vector<Index>, 3> patch_nodes;     // per patch: (i, a, b) → gridpoint
  for (int k = 0; k < 3; ++k) {
    std::vector<Index>& nodes = patch_nodes[std::size_t(k)];
    nodes.resize((nr + 1) * (n + 1) * (n + 1));
    for (Index b = 0; b <= n; ++b)
      for (Index a = 0; a <= n; ++a) {
        const Vec3 direction = patch_direction(k, a, b, n);
        for (Index i = 0; i <= nr; ++i) {
          const Vec3 x = radii[i] * direction;
          const auto [it, inserted] = index_of.try_emplace({x.x(), x.y(), x.z()}, mesh.points.size());
          if (inserted) mesh.points.push_back(x);
          nodes[i + (nr + 1) * (a + (n + 1) * b)] = it->second;
        }
      }
  }

  const std::array<Index, 3> counts = {nr, n, n};
  const char* plane_names[3] = {"xmin", "ymin", "zmin"};
  for (int k = 0; k < 3; ++k) {
    const std::vector<Index>& nodes = patch_nodes[std::size_t(k)];
    const detail::LatticeNodeIndex node = [&nodes, nr, n](Index i, Index a, Index b) { return nodes[i + (nr + 1) * (a + (n + 1) * b)]; };
    detail::add_lattice_zones(mesh, counts, node);
    detail::add_lattice_face_group(mesh, "inner", counts, node, 0, 0);
    detail::add_lattice_face_group(mesh, "outer", counts, node, 0, 1);
    // Edge s = 0 (A→D) lies in the plane of e_k and e_{k+2}: coordinate k+1 is zero;
    // edge t = 0 (A→B) in the plane of e_k and e_{k+1}: coordinate k+2 is zero.
    detail::add_lattice_face_group(mesh, plane_names[(k + 1) % 3], counts, node, 1, 0);
    detail::add_lattice_face_group(mesh, plane_names[(k + 2) % 3], counts, node, 2, 0);
  }
  check_aspect_ratios(mesh, spec.max_aspect_ratio, "sphere_cavity_octant mesh");
  return mesh;
}

}  // namespace dfc::fdm
