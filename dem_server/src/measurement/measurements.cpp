#include "dfc/dem/measurements.hpp"

#include <limits>

namespace dfc::dem {

Measurements measure(const Simulation& sim) {
  // Serial sums in slot / contact order: reproducible for any thread count.
  Measurements m;
  const ParticleStore& p = sim.particles();
  const double g = norm(sim.settings().gravity);
  m.particle_count = p.size();
  double unbalanced = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    m.kinetic_energy += 0.5 * p.mass[i] * norm2(p.velocity[i]) + 0.5 * p.inertia[i] * norm2(p.angular_velocity[i]);
    m.total_weight += p.mass[i] * g;
    unbalanced += norm(p.force[i]);
  }
  if (!sim.contact_outputs_complete()) {
    // A step in the middle of a run failed (the server then still answers
    // queries): its contact outputs are partial, so the contact measures are unknown.
    m.coordination_number = m.unbalanced_force_ratio = std::numeric_limits<double>::quiet_NaN();
    return m;
  }
  const ContactOutputs& out = sim.contact_outputs();
  double contact_force_sum = 0.0;
  const std::size_t pairs = sim.pair_contacts().size();
  for (std::size_t k = 0; k < out.force.size(); ++k) {
    const double f = norm(out.force[k]);
    if (f == 0.0) continue;
    contact_force_sum += f;
    ++(k < pairs ? m.pair_contact_count : m.wall_contact_count);
  }
  if (m.particle_count > 0) m.coordination_number = double(2 * m.pair_contact_count + m.wall_contact_count) / double(m.particle_count);
  const double mean_unbalanced = m.particle_count > 0 ? unbalanced / double(m.particle_count) : 0.0;
  const double mean_applied = m.contact_count() > 0 ? contact_force_sum / double(m.contact_count())
                              : m.particle_count > 0 ? m.total_weight / double(m.particle_count)
                                                     : 0.0;
  m.unbalanced_force_ratio = mean_applied > 0.0 ? mean_unbalanced / mean_applied : 0.0;
  return m;
}

}  // namespace dfc::dem
