#include "dfc/dem/measurements.hpp"

#include <array>
#include <limits>

#include "dfc/dem/exact_sum.hpp"

namespace dfc::dem {

Measurements measure(const Simulation& sim) {
  // Exact sums (exact_sum.hpp): the same bits for any thread count and any
  // split of the particles, computed on all threads (every coupled advance measures).
  Measurements m;
  const ParticleStore& p = sim.particles();
  const double g = norm(sim.settings().gravity);
  m.particle_count = p.size();
  const auto [kinetic_energy, weight, unbalanced] = exact_sums<3>(p.size(), sim.threads(), [&](std::size_t i) {
    return std::array<double, 3>{0.5 * p.mass[i] * norm2(p.velocity[i]) + 0.5 * p.inertia[i] * norm2(p.angular_velocity[i]), p.mass[i] * g,
                                 norm(p.force[i])};
  });
  m.kinetic_energy = kinetic_energy;
  m.total_weight = weight;
  if (!sim.contact_outputs_complete()) {
    // A step in the middle of a run failed (the server then still answers
    // queries): its contact outputs are partial, so the contact measures are unknown.
    m.coordination_number = m.unbalanced_force_ratio = std::numeric_limits<double>::quiet_NaN();
    return m;
  }
  const ContactOutputs& out = sim.contact_outputs();
  const std::size_t pairs = sim.pair_contacts().size();
  const double contact_force_sum = exact_sums<1>(out.force.size(), sim.threads(), [&](std::size_t k) {
    return std::array<double, 1>{norm(out.force[k])};  // a zero (an open contact) adds nothing
  })[0];
  // Counts are integers: their sum is exact in any order.
  std::int64_t pair_count = 0, wall_count = 0;
  const auto outputs = std::int64_t(out.force.size());
#pragma omp parallel for schedule(static) num_threads(sim.threads()) reduction(+ : pair_count, wall_count) if(outputs >= min_parallel_items)
  for (std::int64_t k = 0; k < outputs; ++k) {
    if (norm2(out.force[std::size_t(k)]) == 0.0) continue;  // as the force sum: a zero norm adds nothing
    if (std::size_t(k) < pairs) ++pair_count;
    else ++wall_count;
  }
  m.pair_contact_count = std::size_t(pair_count);
  m.wall_contact_count = std::size_t(wall_count);
  if (m.particle_count > 0) m.coordination_number = double(2 * m.pair_contact_count + m.wall_contact_count) / double(m.particle_count);
  const double mean_unbalanced = m.particle_count > 0 ? unbalanced / double(m.particle_count) : 0.0;
  const double mean_applied = m.contact_count() > 0 ? contact_force_sum / double(m.contact_count())
                              : m.particle_count > 0 ? m.total_weight / double(m.particle_count)
                                                     : 0.0;
  m.unbalanced_force_ratio = mean_applied > 0.0 ? mean_unbalanced / mean_applied : 0.0;
  return m;
}

}  // namespace dfc::dem
