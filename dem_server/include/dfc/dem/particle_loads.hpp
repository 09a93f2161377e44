#pragma once
// A particle's resultant force and moment, summed over its contacts in the
// fixed order of Incidence (contact_lists.hpp) and started from gravity.
//
// Two places add contacts: the pair loop (contact_kernels.hpp), for the prefix
// of each particle's list that its range owns, and the gather before the law
// of motion (integrator.cpp) for the rest. Both use add_contact_load, so each
// term is formed and added by the same operations and the sum does not depend
// on where it was made (bit-identical for any thread count).
#include <cstdint>

#include "dfc/dem/contact_lists.hpp"
#include "dfc/dem/particle_store.hpp"

namespace dfc::dem {

/// Every particle's resultant restarts at its weight m g, with no moment.
void start_particle_loads(ParticleStore& particles, const Vec3& gravity, int threads);

/// Adds force `f` on the particle acting at `arm` from its centre.
inline void add_contact_load(Vec3& force, Vec3& moment, const Vec3& f, const Vec3& arm) noexcept {
  force += f;
  moment += cross(arm, f);
}

/// Adds particle i's Incidence entries from gather_from[i] on to force and moment.
/// Periodic: a pair's second body takes its lever arm from its image next to
/// the first body (contacts.shift).
template <bool Periodic>
void gather_contact_loads(std::size_t i, const Vec3& xi, const Incidence& incidence, const ContactOutputs& contacts, Vec3& force,
                          Vec3& moment) noexcept {
  const bool with_couple = !contacts.couple.empty();
  for (std::uint32_t e = incidence.gather_from[i]; e < incidence.start[i + 1]; ++e) {
    const std::uint32_t entry = incidence.entry[e];
    const std::uint32_t c = entry >> 1;
    // The second body of a pair receives the opposite force and couple. A
    // multiplication by +-1 (exact) instead of a branch: the role is random.
    const double sign = 1.0 - 2.0 * double(entry & 1u);
    const Vec3 f = sign * contacts.force[c];
    if constexpr (Periodic) {
      add_contact_load(force, moment, f, (entry & 1u) != 0 ? contacts.point[c] - (xi + contacts.shift[c]) : contacts.point[c] - xi);
    } else {
      add_contact_load(force, moment, f, contacts.point[c] - xi);
    }
    if (with_couple) moment += sign * contacts.couple[c];
  }
}

}  // namespace dfc::dem
