#include "dfc/dem/integrator.hpp"
#include "dfc/dem/parallel.hpp"
#include "dfc/dem/particle_loads.hpp"

#include <algorithm>
#include <cstdint>

namespace dfc::dem {

namespace {

template <bool Periodic>
MotionReport integrate(ParticleStore& p, const Incidence& incidence, const ContactOutputs& contacts, std::span<const Vec3> reference_positions,
                       const MotionSettings& s, int threads) {
  const auto n = static_cast<std::int64_t>(p.size());
  const double dt = s.dt;
  const bool damped = s.local_damping != 0.0;
  double max_d2 = 0.0;
  bool finite = true;
#pragma omp parallel for schedule(static) num_threads(threads) if(n >= min_parallel_items) reduction(max : max_d2) reduction(&& : finite)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = std::size_t(ii);
    const Vec3 xi = p.position[i];
    // The pair loop already added the first part of the sum (particle_loads.hpp).
    Vec3 force = p.force[i];
    Vec3 moment = p.moment[i];
    gather_contact_loads<Periodic>(i, xi, incidence, contacts, force, moment);
    p.force[i] = force;
    p.moment[i] = moment;

    Vec3 v = p.velocity[i];
    Vec3 w = p.angular_velocity[i];
    // Without damping, F_d = F - 0 |F| sgn(v) is F bit for bit (the product is
    // +-0, and x - (+-0) only turns a -0 into +0, which then adds nothing to a
    // nonzero v; with v = +-0, sgn(v) = 0 and the product is +0), so the sign
    // tests are skipped: in a jittering packing they are random branches.
    if (damped) {
      const Vec3 damped_force = local_damping(force, v, s.local_damping);
      if (!s.damping_force.empty()) s.damping_force[i] = damped_force - force;
      v += (dt / p.mass[i]) * damped_force;
      w += (dt / p.inertia[i]) * local_damping(moment, w, s.local_damping);
    } else {
      v += (dt / p.mass[i]) * force;
      w += (dt / p.inertia[i]) * moment;
    }
    const Vec3 x = xi + dt * v;
    p.velocity[i] = v;
    p.angular_velocity[i] = w;
    p.position[i] = x;
    const double d2 = norm2(x - reference_positions[i]);
    max_d2 = std::max(max_d2, d2);
    finite = finite && std::isfinite(d2) && is_finite(w);
  }
  return {max_d2, finite};
}

}  // namespace

MotionReport integrate_motion(ParticleStore& p, const Incidence& incidence, const ContactOutputs& contacts,
                              std::span<const Vec3> reference_positions, const MotionSettings& s, int threads) {
  if (!contacts.shift.empty()) return integrate<true>(p, incidence, contacts, reference_positions, s, threads);
  return integrate<false>(p, incidence, contacts, reference_positions, s, threads);
}

}  // namespace dfc::dem
