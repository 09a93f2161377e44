// Thick-walled cylinder (or a sector of it) around a cylindrical cavity:
// lattice directions (radial, around, vertical), which is right-handed because
// e_r × e_θ = e_z, so the FLAC3D corner order gives positive tetrahedra.
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "dfc/common/errors.hpp"
#include "dfc/fdm/grading.hpp"
#include "dfc/fdm/mesh_generators.hpp"
#include "dfc/fdm/mesh_quality.hpp"
#include "disc_ogrid.hpp"
#include "structured_mesh.hpp"

namespace dfc::fdm {

std::vector<double> graded_radii(const CylinderCavitySpec& spec) {
  return geometric_spacing(spec.inner_radius, spec.outer_radius, spec.zones_radial, spec.grading_ratio);
}

namespace {

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// The floor's level k as a real number: (floor - z_bottom) / layer thickness.
double floor_layers(const CylinderCavitySpec& spec) {
  return (*spec.cavity_floor_z - spec.z_bottom) / (spec.height / double(spec.zones_vertical));
}

}  // namespace

std::optional<CavityFloorProblem> cavity_floor_problem(const CylinderCavitySpec& spec) {
  if (!spec.cavity_floor_z) return std::nullopt;
  const double floor = *spec.cavity_floor_z, top = spec.z_bottom + spec.height;
  if (!(floor > spec.z_bottom && floor < top))
    return CavityFloorProblem{"cavity_floor_z_m", "the cavity's floor must lie above z_bottom_m (" + format_number(spec.z_bottom) +
                                                      ") and below z_bottom_m + height_m (" + format_number(top) +
                                                      "); z_bottom_m (the default) for a cavity through the whole height"};
  if (spec.angle_deg != 360.0)
    return CavityFloorProblem{"angle_deg", "a cavity floor (the solid base below it) needs the full circle: angle_deg 360"};
  if (spec.zones_around % 4 != 0)
    return CavityFloorProblem{"zones_around", "a cavity floor needs zones_around to be a multiple of 4 (the O-grid of the base takes a quarter "
                                              "on each side of its core), got " + std::to_string(spec.zones_around)};
  // The layers are uniform, height / zones_vertical: the floor must be one of their levels.
  const double layers = floor_layers(spec), layer = spec.height / double(spec.zones_vertical);
  if (std::abs(layers - std::round(layers)) > 1e-9 * double(spec.zones_vertical))
    return CavityFloorProblem{"cavity_floor_z_m", "the cavity's floor must lie on a zone level (the layers are height_m / zones_vertical = " +
                                                      format_number(layer) + " m thick): the nearest are " +
                                                      format_number(spec.z_bottom + std::floor(layers) * layer) + " and " +
                                                      format_number(spec.z_bottom + std::ceil(layers) * layer) + " m; change it or zones_vertical"};
  return std::nullopt;
}

Index cavity_floor_level(const CylinderCavitySpec& spec) {
  if (!spec.cavity_floor_z) return 0;
  if (const auto problem = cavity_floor_problem(spec)) throw UserError("cylinder_cavity: " + problem->message);
  return Index(std::lround(floor_layers(spec)));
}

Mesh make_cylinder_cavity(const CylinderCavitySpec& spec) {
  if (!(spec.inner_radius > 0.0) || !(spec.outer_radius > spec.inner_radius))
    throw UserError("cylinder_cavity: need 0 < inner_radius < outer_radius");
  if (!(spec.height > 0.0)) throw UserError("cylinder_cavity: height must be > 0");
  if (!(spec.angle_deg > 0.0 && spec.angle_deg <= 360.0)) throw UserError("cylinder_cavity: angle_deg must be in (0, 360]");
  const bool full_circle = spec.angle_deg == 360.0;
  if (spec.zones_radial < 1 || spec.zones_around < (full_circle ? 3u : 1u) || spec.zones_vertical < 1)
    throw UserError("cylinder_cavity: need zones_radial >= 1, zones_around >= 3 (>= 1 for a sector), zones_vertical >= 1");
  if (!(spec.grading_ratio > 0.0)) throw UserError("cylinder_cavity: grading_ratio must be > 0");
  const Index floor_level = spec.cavity_floor_z ? cavity_floor_level(spec) : 0;

  const Index nr = spec.zones_radial;
  const Index nt = spec.zones_around;
  const Index nz = spec.zones_vertical;
  const Index rings_around = full_circle ? nt : nt + 1;  // a full circle does not repeat θ = 360°
  const std::vector<double> radii = graded_radii(spec);
  const double angle = spec.angle_deg * std::numbers::pi / 180.0;

  Mesh mesh;
  mesh.points.reserve((nr + 1) * rings_around * (nz + 1));
  for (Index k = 0; k <= nz; ++k) {
    const double z = spec.z_bottom + spec.height * double(k) / double(nz);
    for (Index j = 0; j < rings_around; ++j) {
      const double theta = angle * double(j) / double(nt);
      // Exact zeros on the coordinate planes (θ = 90°, 180°, …), so that a
      // sector side there is exactly axis-aligned and takes a roller.
      const auto snap = [](double v) { return std::abs(v) < 1e-14 ? 0.0 : v; };
      const double c = snap(std::cos(theta));
      const double s = snap(std::sin(theta));
      for (Index i = 0; i <= nr; ++i) mesh.points.emplace_back(radii[i] * c, radii[i] * s, z);
    }
  }

  const std::array<Index, 3> counts = {nr, nt, nz};
  // Full circle: j wraps (lattice node j = nt is gridpoint j = 0), so the seam has no duplicates.
  const detail::LatticeNodeIndex node = [nr, rings_around](Index i, Index j, Index k) {
    return i + (nr + 1) * ((j % rings_around) + rings_around * k);
  };
  detail::add_lattice_zones(mesh, counts, node);
  if (spec.cavity_floor_z) {
    // The cavity's side is the annulus's inner face above the floor level; the
    // O-grid fills the disc below it, and its top is the cavity's floor.
    const std::array<Index, 3> above = {nr, nt, nz - floor_level};
    const detail::LatticeNodeIndex node_above = [&node, floor_level](Index i, Index j, Index k) { return node(i, j, k + floor_level); };
    detail::add_lattice_face_group(mesh, "inner", above, node_above, 0, 0);
    detail::add_lattice_face_group(mesh, "cavity_side", above, node_above, 0, 0);
    const detail::CircleNode circle = [&node](Index j, Index k) { return node(0, j, k); };
    detail::add_disc_ogrid(mesh, nt, floor_level, circle, "bottom", {"inner", "cavity_floor"});
  } else {
    detail::add_lattice_face_group(mesh, "inner", counts, node, 0, 0);
  }
  detail::add_lattice_face_group(mesh, "outer", counts, node, 0, 1);
  detail::add_lattice_face_group(mesh, "bottom", counts, node, 2, 0);
  detail::add_lattice_face_group(mesh, "top", counts, node, 2, 1);
  if (!full_circle) {
    detail::add_lattice_face_group(mesh, "theta_min", counts, node, 1, 0);
    detail::add_lattice_face_group(mesh, "theta_max", counts, node, 1, 1);
  }
  check_aspect_ratios(mesh, spec.max_aspect_ratio, "cylinder_cavity mesh");
  return mesh;
}

}  // namespace dfc::fdm
