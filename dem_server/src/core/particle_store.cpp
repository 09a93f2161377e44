#include "dfc/dem/particle_store.hpp"

#include <algorithm>
#include <numbers>
#include <string>

#include "dfc/common/errors.hpp"
#include "dfc/dem/parallel.hpp"

namespace dfc::dem {

void ParticleStore::add_sphere(std::int64_t particle_id, Vec3 x, double r, double density, std::uint16_t material_id) {
  if (!(r > 0.0) || !(density > 0.0))
    throw UserError("particle " + std::to_string(particle_id) + " needs a positive radius and density (got r = " + std::to_string(r) +
                    " m, rho = " + std::to_string(density) + " kg/m3)");
  const double m = density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  id.push_back(particle_id);
  position.push_back(x);
  velocity.push_back({});
  angular_velocity.push_back({});
  force.push_back({});
  moment.push_back({});
  radius.push_back(r);
  mass.push_back(m);
  inertia.push_back(0.4 * m * r * r);  // solid sphere, I = 2/5 m r^2
  material.push_back(material_id);
}

void ParticleStore::set_radius(std::size_t slot, double r) {
  if (!(r > 0.0)) throw UserError("particle " + std::to_string(id.at(slot)) + " needs a positive radius (got " + std::to_string(r) + " m)");
  const double scale = r / radius[slot];
  radius[slot] = r;
  mass[slot] *= scale * scale * scale;          // same density
  inertia[slot] = 0.4 * mass[slot] * r * r;     // solid sphere, I = 2/5 m r^2
}

namespace {
template <class T>
void permute_field(std::vector<T>& field, std::span<const std::uint32_t> new_to_old, int threads) {
  std::vector<T> out(new_to_old.size());
  const auto n = std::int64_t(new_to_old.size());
#pragma omp parallel for schedule(static) num_threads(threads) if(n >= min_parallel_items)
  for (std::int64_t k = 0; k < n; ++k) out[std::size_t(k)] = field[new_to_old[std::size_t(k)]];
  field.swap(out);
}
}  // namespace

void ParticleStore::permute(std::span<const std::uint32_t> new_to_old, int threads) {
  permute_field(id, new_to_old, threads);
  permute_field(position, new_to_old, threads);
  permute_field(velocity, new_to_old, threads);
  permute_field(angular_velocity, new_to_old, threads);
  permute_field(force, new_to_old, threads);
  permute_field(moment, new_to_old, threads);
  permute_field(radius, new_to_old, threads);
  permute_field(mass, new_to_old, threads);
  permute_field(inertia, new_to_old, threads);
  permute_field(material, new_to_old, threads);
}

void ParticleStore::retain(std::span<const std::uint32_t> kept_slots) { permute(kept_slots); }

double sphere_volume_sum(const ParticleStore& particles) noexcept {
  double solid = 0.0;
  for (const double r : particles.radius) solid += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return solid;
}

double largest_radius(const ParticleStore& particles) noexcept {
  double r_max = 0.0;
  for (const double r : particles.radius) r_max = std::max(r_max, r);
  return r_max;
}

}  // namespace dfc::dem
