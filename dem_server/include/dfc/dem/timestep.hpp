#pragma once
// Critical time step of the centred-difference scheme (integrator.hpp).
//
// A mass m on a spring k oscillates at w = sqrt(k/m); the leapfrog scheme is
// stable for dt < 2/w (e.g. Belytschko, Liu & Moran, Nonlinear Finite
// Elements, 2000, §6.3.2). Per particle this code takes
//
//   dt_crit = min_i sqrt(m_i / k_i),   k_i = max(k_n, (1 + m_i r_i^2 / I_i) k_s)
//
// over every active law (particle–particle and each wall's), following PFC's
// sqrt(m/k) estimate. The factor 1 + m r^2/I (= 3.5 for a solid sphere)
// accounts for the rotation the shear spring drives. Margins: an isolated
// equal pair is stable up to sqrt(2) dt_crit, a single wall contact up to
// 2 dt_crit; a particle with Z contacts is stiffer by up to ~Z, which is why
// scenarios run at a fraction of dt_crit (0.2 by default, as PFC applies a
// safety factor to its estimate).
#include <span>

#include "dfc/dem/contact_model.hpp"
#include "dfc/dem/particle_store.hpp"

namespace dfc::dem {

/// +infinity when there are no particles or no stiffness.
[[nodiscard]] double critical_timestep(const ParticleStore& particles, std::span<const StiffnessBound> laws);

}  // namespace dfc::dem
