// Thick-walled cylinder around a cylindrical cavity: lattice directions
// (radial, around, vertical), which is right-handed because e_r × e_θ = e_z,
// so the FLAC3D corner order gives positive tetrahedra.
#include <cmath>
#include <numbers>

#include "dfc/common/errors.hpp"
#include "dfc/fdm/mesh_generators.hpp"
#include "structured_mesh.hpp"

namespace dfc::fdm {

std::vector<double> graded_radii(const CylinderCavitySpec& spec) {
  const Index n = spec.zones_radial;
  const double ratio = spec.grading_ratio;
  const double thickness = spec.outer_radius - spec.inner_radius;
  // Geometric series Δr_k = Δr_0 qᵏ with Σ Δr_k = Ro − Ri; q = 1 is the uniform limit.
  const bool uniform = std::abs(ratio - 1.0) < 1e-12;
  const double first = uniform ? thickness / double(n) : thickness * (ratio - 1.0) / (std::pow(ratio, double(n)) - 1.0);
  std::vector<double> radii;
  radii.reserve(n + 1);
  radii.push_back(spec.inner_radius);
  double step = first;
  for (Index k = 1; k < n; ++k) {
    radii.push_back(radii.back() + step);
    step *= ratio;
  }
  radii.push_back(spec.outer_radius);  // exact, not accumulated
  return radii;
}

Mesh make_cylinder_cavity(const CylinderCavitySpec& spec) {
  if (!(spec.inner_radius > 0.0) || !(spec.outer_radius > spec.inner_radius))
    throw UserError("cylinder_cavity: need 0 < inner_radius < outer_radius");
  if (!(spec.height > 0.0)) throw UserError("cylinder_cavity: height must be > 0");
  if (spec.zones_radial < 1 || spec.zones_around < 3 || spec.zones_vertical < 1)
    throw UserError("cylinder_cavity: need zones_radial >= 1, zones_around >= 3, zones_vertical >= 1");
  if (!(spec.grading_ratio > 0.0)) throw UserError("cylinder_cavity: grading_ratio must be > 0");

  const Index nr = spec.zones_radial;
  const Index nt = spec.zones_around;
  const Index nz = spec.zones_vertical;
  const std::vector<double> radii = graded_radii(spec);

  Mesh mesh;
  mesh.points.reserve((nr + 1) * nt * (nz + 1));
  for (Index k = 0; k <= nz; ++k) {
    const double z = spec.z_bottom + spec.height * double(k) / double(nz);
    for (Index j = 0; j < nt; ++j) {
      const double angle = 2.0 * std::numbers::pi * double(j) / double(nt);
      for (Index i = 0; i <= nr; ++i) mesh.points.emplace_back(radii[i] * std::cos(angle), radii[i] * std::sin(angle), z);
    }
  }

  const std::array<Index, 3> counts = {nr, nt, nz};
  // j wraps: lattice node j = nt is gridpoint j = 0, so the 0/360° seam has no duplicates.
  const detail::LatticeNodeIndex node = [nr, nt](Index i, Index j, Index k) { return i + (nr + 1) * ((j % nt) + nt * k); };
  detail::add_lattice_zones(mesh, counts, node);
  detail::add_lattice_face_group(mesh, "inner", counts, node, 0, 0);
  detail::add_lattice_face_group(mesh, "outer", counts, node, 0, 1);
  detail::add_lattice_face_group(mesh, "bottom", counts, node, 2, 0);
  detail::add_lattice_face_group(mesh, "top", counts, node, 2, 1);
  return mesh;
}

}  // namespace dfc::fdm
