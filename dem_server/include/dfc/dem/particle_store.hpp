#pragma once
// ParticleStore: the spheres as a structure of arrays (CONTRIBUTING.md §4).
//
// One std::vector per field, indexed by *slot*. Slots are an implementation
// detail: the neighbour search re-sorts them spatially at every rebuild for
// cache locality. The stable name of a particle is its `id`, which outputs,
// contact history and restarts use.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "dfc/dem/vec3.hpp"

namespace dfc::dem {

struct ParticleStore {
  std::vector<std::int64_t> id;
  std::vector<Vec3> position;          ///< m
  std::vector<Vec3> velocity;          ///< m/s (leapfrog: at the half step, see integrator.hpp)
  std::vector<Vec3> angular_velocity;  ///< rad/s (half step)
  std::vector<Vec3> force;             ///< N, resultant of the last force evaluation (contacts + gravity, undamped)
  std::vector<Vec3> moment;            ///< N m, resultant moment of the last force evaluation
  std::vector<double> radius;          ///< m
  std::vector<double> mass;            ///< kg
  std::vector<double> inertia;         ///< kg m^2, 2/5 m r^2 for a solid sphere
  /// Material (particle_materials.hpp): which contact-law parameter set the
  /// particle's pairs use; a zone of a graded model (0 without zones).
  std::vector<std::uint16_t> material;

  [[nodiscard]] std::size_t size() const noexcept { return id.size(); }

  /// Appends a solid sphere at rest. Throws UserError for a non-positive
  /// radius or density.
  void add_sphere(std::int64_t particle_id, Vec3 x, double r, double density, std::uint16_t material_id = 0);

  /// Sets the radius of `slot`, keeping its density: mass and inertia follow
  /// (radius expansion, radius_expansion.hpp). Throws UserError for r <= 0.
  void set_radius(std::size_t slot, double r);

  /// Reorders every field: new slot k takes old slot new_to_old[k]. On
  /// `threads` threads (a rebuild of the paper model re-sorts 550 000
  /// particles; a gather, so any split gives the same fields).
  void permute(std::span<const std::uint32_t> new_to_old, int threads = 1);
  /// Keeps only `kept_slots` (increasing), in that order; the others are removed.
  void retain(std::span<const std::uint32_t> kept_slots);
};

/// m3, sum of the sphere volumes 4/3 pi r^3 (overlaps not subtracted: PFC's
/// convention for the porosity of a sample).
[[nodiscard]] double sphere_volume_sum(const ParticleStore& particles) noexcept;

/// m, the largest radius (0 without particles).
[[nodiscard]] double largest_radius(const ParticleStore& particles) noexcept;

}  // namespace dfc::dem
