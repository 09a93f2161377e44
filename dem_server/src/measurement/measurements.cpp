#include "dfc/dem/measurements.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "dfc/dem/exact_sum.hpp"

namespace dfc::dem {

MeasureSums measure_sums(const Simulation& sim, std::span<const std::uint8_t> owned) {
  // Exact sums (exact_sum.hpp): the same bits for any thread count and any
  // split of the particles, computed on all threads (every coupled advance measures).
  MeasureSums m;
  const ParticleStore& p = sim.particles();
  const bool all = owned.empty();
  const double g = norm(sim.settings().gravity);
  const auto particle_sums = exact_accumulators<3>(p.size(), sim.threads(), [&](std::size_t i) {
    if (!all && !owned[i]) return std::array<double, 3>{};
    return std::array<double, 3>{0.5 * p.mass[i] * norm2(p.velocity[i]) + 0.5 * p.inertia[i] * norm2(p.angular_velocity[i]), p.mass[i] * g,
                                 norm(p.force[i])};
  });
  for (std::size_t k = 0; k < 3; ++k) m.sums[k] = particle_sums[k];
  m.particles = all ? std::int64_t(p.size()) : std::int64_t(std::count(owned.begin(), owned.end(), std::uint8_t{1}));
  m.outputs_complete = sim.contact_outputs_complete();
  if (!m.outputs_complete) return m;
  const ContactOutputs& out = sim.contact_outputs();
  const PairContacts& pair_lists = sim.pair_contacts();
  const std::size_t pairs = pair_lists.size();
  // Which outputs count: pairs of an owned first particle, wall contacts of an owned particle.
  std::vector<std::uint8_t> counted;
  if (!all) {
    counted.resize(out.force.size(), 0);
    for (std::size_t k = 0; k < pairs; ++k) counted[k] = owned[pair_lists.first[k]];
    for (std::size_t w = 0; w < sim.walls().size(); ++w) {
      const WallContacts& contacts = sim.wall_contacts(w);
      for (std::size_t k = 0; k < contacts.size(); ++k) counted[sim.wall_output_offset(w) + k] = owned[contacts.particle[k]];
    }
  }
  m.sums[3] = exact_accumulators<1>(out.force.size(), sim.threads(), [&](std::size_t k) {
    return std::array<double, 1>{all || counted[k] ? norm(out.force[k]) : 0.0};  // a zero (an open contact) adds nothing
  })[0];
  // Counts are integers: their sum is exact in any order.
  std::int64_t pair_count = 0, wall_count = 0;
  const auto outputs = std::int64_t(out.force.size());
#pragma omp parallel for schedule(static) num_threads(sim.threads()) reduction(+ : pair_count, wall_count) if(outputs >= min_parallel_items)
  for (std::int64_t k = 0; k < outputs; ++k) {
    if (norm2(out.force[std::size_t(k)]) == 0.0 || !(all || counted[std::size_t(k)])) continue;  // as the force sum: a zero norm adds nothing
    if (std::size_t(k) < pairs) ++pair_count;
    else ++wall_count;
  }
  m.pair_contacts = pair_count;
  m.wall_contacts = wall_count;
  return m;
}

Measurements measurements_from(const MeasureSums& sums) {
  Measurements m;
  m.particle_count = std::size_t(sums.particles);
  m.kinetic_energy = sums.sums[0].value();
  m.total_weight = sums.sums[1].value();
  const double unbalanced = sums.sums[2].value();
  if (!sums.outputs_complete) {
    // A step in the middle of a run failed (the server then still answers
    // queries): its contact outputs are partial, so the contact measures are unknown.
    m.coordination_number = m.unbalanced_force_ratio = std::numeric_limits<double>::quiet_NaN();
    return m;
  }
  const double contact_force_sum = sums.sums[3].value();
  m.pair_contact_count = std::size_t(sums.pair_contacts);
  m.wall_contact_count = std::size_t(sums.wall_contacts);
  if (m.particle_count > 0) m.coordination_number = double(2 * m.pair_contact_count + m.wall_contact_count) / double(m.particle_count);
  const double mean_unbalanced = m.particle_count > 0 ? unbalanced / double(m.particle_count) : 0.0;
  const double mean_applied = m.contact_count() > 0 ? contact_force_sum / double(m.contact_count())
                              : m.particle_count > 0 ? m.total_weight / double(m.particle_count)
                                                     : 0.0;
  m.unbalanced_force_ratio = mean_applied > 0.0 ? mean_unbalanced / mean_applied : 0.0;
  return m;
}

Measurements measure(const Simulation& sim) { return measurements_from(measure_sums(sim)); }

}  // namespace dfc::dem
