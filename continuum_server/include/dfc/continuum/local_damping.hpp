#pragma once
// Local non-viscous damping of the explicit step (Cundall 1987; theory/fdm.md
// §1.9) for one velocity component, and its inverse: the force that gives a
// wanted velocity change (the kinematic pile contact, rigid_pile.hpp).
namespace dfc::continuum {

/// Velocity change of one component under the unbalanced force `force`:
/// Δv = (F − α|F| sgn v)/m, v the velocity of the previous half step.
[[nodiscard]] double damped_velocity_change(double force, double velocity, double mass, double damping);

/// The unbalanced force F for which damped_velocity_change gives `change`:
/// F(1 − α s sgn F) = m Δv with s = sgn v; F has the sign of Δv because
/// 1 − α > 0, so F = m Δv/(1 − α s sgn Δv).
[[nodiscard]] double force_for_velocity_change(double change, double velocity, double mass, double damping);

}  // namespace dfc::continuum
