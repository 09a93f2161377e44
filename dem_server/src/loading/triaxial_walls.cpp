#include "dfc/dem/triaxial_walls.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "dfc/common/errors.hpp"
#include "dfc/dem/particle_store.hpp"
#include "dfc/dem/ucs_platens.hpp"

namespace dfc::dem {

namespace {

/// Outward unit normals in BoxStress order.
std::array<Vec3, 6> outward(const BoxAxes& axes) {
  return {axes.axis, -1.0 * axes.axis, -1.0 * axes.lateral[0], axes.lateral[0], -1.0 * axes.lateral[1], axes.lateral[1]};
}

/// m2, the loaded area of each wall and m, the sample extent along its normal.
std::array<double, 6> areas(const BoxSize& s) {
  const double platen = s.width[0] * s.width[1];
  return {platen, platen, s.height * s.width[1], s.height * s.width[1], s.height * s.width[0], s.height * s.width[0]};
}
std::array<double, 6> extents(const BoxSize& s) { return {s.height, s.height, s.width[0], s.width[0], s.width[1], s.width[1]}; }

/// Contacts of wall w that carried a force in the last step.
/// The contacts of wall w that carry a force, over the whole body (each
/// counted by the process that owns its particle; collective).
std::size_t loaded_contacts(const DemEngine& engine, std::size_t w) {
  const Simulation& sim = engine.part();
  const ContactOutputs& out = sim.contact_outputs();
  const std::size_t offset = sim.wall_output_offset(w);
  const WallContacts& contacts = sim.wall_contacts(w);
  std::array<ExactSum, 1> loaded{};
  for (std::size_t k = 0; k < contacts.size(); ++k)
    if (engine.owns(contacts.particle[k]) && norm2(out.force[offset + k]) > 0.0) loaded[0].add(1.0);
  engine.sum_over_processes(loaded);
  return std::size_t(loaded[0].value());  // a count below 2^53: exact
}

Vec3 unit_between(const Vec3& from, const Vec3& to, const std::string& what) {
  const Vec3 d = to - from;
  const double l = norm(d);
  if (!(l > 0.0)) throw UserError("the two " + what + " have the same centroid; they must face each other across the sample");
  return (1.0 / l) * d;
}

}  // namespace

BoxVertices box_vertices(std::span<const Wall> walls, const TriaxialWalls& box) {
  const auto order = box.in_order();
  BoxVertices v;
  for (std::size_t k = 0; k < 6; ++k) v[k] = walls[order[k]].vertices;
  return v;
}

BoxAxes box_axes(const BoxVertices& v) {
  BoxAxes axes;
  axes.axis = unit_between(vertex_centroid(v[1]), vertex_centroid(v[0]), "platens");
  axes.lateral[0] = unit_between(vertex_centroid(v[2]), vertex_centroid(v[3]), "walls of the first lateral pair");
  axes.lateral[1] = unit_between(vertex_centroid(v[4]), vertex_centroid(v[5]), "walls of the second lateral pair");
  // The stresses divide by products of the separations: a skewed box would
  // report wrong areas, so it is refused rather than measured.
  constexpr double tolerance = 1e-6;
  if (std::abs(dot(axes.axis, axes.lateral[0])) > tolerance || std::abs(dot(axes.axis, axes.lateral[1])) > tolerance ||
      std::abs(dot(axes.lateral[0], axes.lateral[1])) > tolerance)
    throw UserError("the platens and the two lateral wall pairs must face each other along three perpendicular directions");
  return axes;
}

BoxSize box_size(std::span<const Wall> walls, const TriaxialWalls& box, const BoxAxes& axes) {
  const BoxVertices v = box_vertices(walls, box);
  const auto separation = [&](std::size_t first, std::size_t second, const Vec3& along) {
    return dot(vertex_centroid(v[second]) - vertex_centroid(v[first]), along);
  };
  return {separation(1, 0, axes.axis), {separation(2, 3, axes.lateral[0]), separation(4, 5, axes.lateral[1])}};
}

BoxStress box_stress(std::span<const Wall> walls, const TriaxialWalls& box, const BoxAxes& axes, const BoxSize& size) {
  const auto order = box.in_order();
  const auto out = outward(axes);
  const auto area = areas(size);
  BoxStress s;
  for (std::size_t k = 0; k < 6; ++k) s.wall[k] = dot(walls[order[k]].force, out[k]) / area[k];
  return s;
}

BoxStress triaxial_step(DemEngine& engine, const TriaxialWalls& box, const BoxAxes& axes, const TriaxialControl& control, double dt) {
  engine.step(dt, ContactRecord::complete);
  Simulation& sim = engine.part();
  const auto order = box.in_order();
  const auto out = outward(axes);
  const BoxSize size = box_size(sim.walls(), box, axes);
  const BoxStress stress = box_stress(sim.walls(), box, axes, size);
  const auto area = areas(size);
  const auto extent = extents(size);
  const double r_max = engine.max_over_processes(largest_radius(sim.particles()));
  for (std::size_t k = 0; k < 6; ++k) {
    const std::size_t w = order[k];
    const bool platen = k < 2;
    if (platen && control.platen_speed) {
      sim.set_wall_velocity(w, -*control.platen_speed * out[k]);
      continue;
    }
    const double kn = sim.walls()[w].law.stiffness_bound(r_max).normal;
    const double cap = 0.5 * control.max_strain_rate * extent[k];
    const double error = control.confining_stress - stress.wall[k];  // > 0: not compressed enough, move in
    const std::size_t contacts = loaded_contacts(engine, w);
    const double inward = contacts > 0 ? control.gain * area[k] * error / (kn * double(contacts) * dt) : (error > 0.0 ? cap : -cap);
    sim.set_wall_velocity(w, -std::clamp(inward, -cap, cap) * out[k]);
  }
  return stress;
}

double box_porosity(const ParticleStore& particles, const BoxSize& size) noexcept { return box_porosity(sphere_volume_sum(particles), size); }

double box_porosity(double solid_volume, const BoxSize& size) noexcept { return 1.0 - solid_volume / size.volume(); }

double confinement_error(const BoxStress& stress, const TriaxialControl& control) noexcept {
  double worst = 0.0;
  for (std::size_t k = control.platen_speed ? 2 : 0; k < 6; ++k)
    worst = std::max(worst, std::abs(control.confining_stress - stress.wall[k]) / control.confining_stress);
  return worst;
}

}  // namespace dfc::dem
