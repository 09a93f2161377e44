#pragma once
// Law of motion: PFC's centred finite-difference scheme (leapfrog; Itasca PFC
// "Law of Motion"; Cundall & Strack 1979) with local non-viscous damping.
//
//   F(t)      = sum of contact forces at x(t) + m g          (in a fixed order per particle)
//   F_d       = F - alpha |F| sgn(v(t - dt/2))                (per component; same for moments)
//   v(t+dt/2) = v(t-dt/2) + F_d / m dt,  omega likewise with I = 2/5 m r^2
//   x(t+dt)   = x(t) + v(t+dt/2) dt
//
// Stored velocities are half-step values; positions are full-step values.
// Spheres have an isotropic inertia tensor, so no gyroscopic term arises.
#include <cmath>
#include <span>

#include "dfc/dem/contact_lists.hpp"
#include "dfc/dem/particle_store.hpp"

namespace dfc::dem {

/// Local (non-viscous) damping of Cundall (1987), per component:
/// F_d = F - alpha |F| sgn(v). A component with v = 0 is undamped.
[[nodiscard]] inline Vec3 local_damping(const Vec3& f, const Vec3& v, double alpha) noexcept {
  const auto damp = [alpha](double fc, double vc) {
    // sgn(v) without branches: velocity signs in a jittering packing are random.
    const double s = double(vc > 0.0) - double(vc < 0.0);
    return fc - alpha * std::abs(fc) * s;
  };
  return {damp(f.x, v.x), damp(f.y, v.y), damp(f.z, v.z)};
}

struct MotionSettings {
  double dt = 0.0;            ///< s
  Vec3 gravity;               ///< m/s^2
  double local_damping = 0.0; ///< alpha in [0, 1)
  /// When not empty (one per particle): each particle's damping force of
  /// this step, F_d - F (N), for the momentum balance (Simulation::damping_force_total).
  std::span<Vec3> damping_force;
};

struct MotionReport {
  double max_displacement2 = 0.0;  ///< m^2, largest |x - x_reference|^2 after the move
  bool finite = true;              ///< false if any position or velocity became non-finite
};

/// Completes every particle's resultant (particle_loads.hpp: the pair loop
/// added the first part of each sum to particles.force/moment, the rest is
/// gathered here in Incidence order), stores it (undamped) in
/// particles.force/moment, and advances velocities and positions by one step.
[[nodiscard]] MotionReport integrate_motion(ParticleStore& particles, const Incidence& incidence, const ContactOutputs& contacts,
                                            std::span<const Vec3> reference_positions, const MotionSettings& settings, int threads);

}  // namespace dfc::dem
