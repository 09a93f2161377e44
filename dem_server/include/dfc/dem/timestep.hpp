#pragma once
// Critical time step of the centred-difference scheme (integrator.hpp).
//
// A mass m on a spring k oscillates at w = sqrt(k/m); the leapfrog scheme is
// stable for dt < 2/w (e.g. Belytschko, Liu & Moran, Nonlinear Finite
// Elements, 2000, §6.3.2). Per particle this code takes
//
//   dt_crit = min_i sqrt(m_i / k_i),   k_i = max(k_n(r), (1 + m_i r_i^2 / I_i) k_s(r))
//
// over every active law (particle–particle and each wall's), following PFC's
// sqrt(m/k) estimate. The factor 1 + m r^2/I (= 3.5 for a solid sphere)
// accounts for the rotation the shear spring drives.
//
// Which r (StepBound): a law's stiffness_bound(r) bounds every contact whose
// radii are at most r. Under the deformability method (bond_geometry.hpp)
// k_n = π E* R_min² / (R1 + R2) <= π E* R_i whatever the partner's radius
// (R_min <= R_i, and R_min² / (R1 + R2) <= R_min / 2 for two spheres, = R_i
// for a facet), so stiffness_bound(r_i) bounds every contact sphere i can
// have: `per_particle`. The older `largest_radius` paired each mass with the
// bound at the largest radius of the body, which for a graded body
// (radii r_min..r_max) is sqrt(r_max / r_min) times smaller than needed for
// the same guarantee (2.5x in the paper's open pile, S = 2.1-4.8 over a PSD
// 0.066-0.18 mm).
//
// Margins (both bounds): the stiffness matrix's largest eigenvalue over the
// masses is at most max_i 2 Σ_j k_ij / m_i (Gershgorin on M⁻¹K), each k_ij <=
// min(k_i, k_j); so an isolated equal pair is stable up to sqrt(2) dt_crit, a
// single wall contact up to 2 dt_crit, and a particle with Z contacts down to
// sqrt(2/Z) dt_crit, which is why scenarios run at a fraction of dt_crit (0.2
// by default, as PFC applies a safety factor to its estimate).
#include <functional>

#include "dfc/dem/contact_model.hpp"
#include "dfc/dem/particle_store.hpp"

namespace dfc::dem {

/// Which radius a sphere's stiffness bound is taken at (dem.timestep.stiffness_bound).
enum class StepBound {
  per_particle,    ///< its own radius: every contact it can have (the default)
  largest_radius,  ///< the body's largest radius, for every sphere (before 2026-12)
};

/// The stiffest translational contact a sphere of radius r can have, over
/// every law it can meet (particle laws and walls); non-decreasing in r.
using StiffnessBoundAt = std::function<StiffnessBound(double radius)>;

/// +infinity when there are no particles or no stiffness.
[[nodiscard]] double critical_timestep(const ParticleStore& particles, const StiffnessBoundAt& bound, StepBound which);

/// The largest of several laws' bounds, for StiffnessBoundAt.
[[nodiscard]] StiffnessBound stiffest(StiffnessBound a, const StiffnessBound& b) noexcept;

}  // namespace dfc::dem
