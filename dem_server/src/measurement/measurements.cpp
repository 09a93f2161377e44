#include "dfc/dem/measurements.hpp"

#include <limits>

#include "dfc/dem/fixed_order_sum.hpp"

namespace dfc::dem {

namespace {

struct ParticleSums {
  double kinetic_energy = 0.0, weight = 0.0, unbalanced = 0.0;
  ParticleSums& operator+=(const ParticleSums& o) noexcept {
    kinetic_energy += o.kinetic_energy;
    weight += o.weight;
    unbalanced += o.unbalanced;
    return *this;
  }
};

struct ContactSums {
  double force = 0.0;
  std::size_t pairs = 0, walls = 0;
  ContactSums& operator+=(const ContactSums& o) noexcept {
    force += o.force;
    pairs += o.pairs;
    walls += o.walls;
    return *this;
  }
};

}  // namespace

Measurements measure(const Simulation& sim) {
  // Sums in the fixed blocked order of fixed_order_sum: the same bits for any
  // thread count, computed on all of them (every coupled advance measures).
  Measurements m;
  const ParticleStore& p = sim.particles();
  const double g = norm(sim.settings().gravity);
  m.particle_count = p.size();
  const auto particles = fixed_order_sum<ParticleSums>(p.size(), sim.threads(), [&](std::size_t i) {
    return ParticleSums{0.5 * p.mass[i] * norm2(p.velocity[i]) + 0.5 * p.inertia[i] * norm2(p.angular_velocity[i]), p.mass[i] * g, norm(p.force[i])};
  });
  m.kinetic_energy = particles.kinetic_energy;
  m.total_weight = particles.weight;
  const double unbalanced = particles.unbalanced;
  if (!sim.contact_outputs_complete()) {
    // A step in the middle of a run failed (the server then still answers
    // queries): its contact outputs are partial, so the contact measures are unknown.
    m.coordination_number = m.unbalanced_force_ratio = std::numeric_limits<double>::quiet_NaN();
    return m;
  }
  const ContactOutputs& out = sim.contact_outputs();
  const std::size_t pairs = sim.pair_contacts().size();
  const auto contacts = fixed_order_sum<ContactSums>(out.force.size(), sim.threads(), [&](std::size_t k) {
    const double f = norm(out.force[k]);
    if (f == 0.0) return ContactSums{};
    return k < pairs ? ContactSums{f, 1, 0} : ContactSums{f, 0, 1};
  });
  const double contact_force_sum = contacts.force;
  m.pair_contact_count = contacts.pairs;
  m.wall_contact_count = contacts.walls;
  if (m.particle_count > 0) m.coordination_number = double(2 * m.pair_contact_count + m.wall_contact_count) / double(m.particle_count);
  const double mean_unbalanced = m.particle_count > 0 ? unbalanced / double(m.particle_count) : 0.0;
  const double mean_applied = m.contact_count() > 0 ? contact_force_sum / double(m.contact_count())
                              : m.particle_count > 0 ? m.total_weight / double(m.particle_count)
                                                     : 0.0;
  m.unbalanced_force_ratio = mean_applied > 0.0 ? mean_unbalanced / mean_applied : 0.0;
  return m;
}

}  // namespace dfc::dem
