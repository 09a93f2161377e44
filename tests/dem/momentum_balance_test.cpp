// The particles' momentum balance from the DEM's monitors (SPEC.md §6.3):
//   d(Σ m v)/dt = weight - Σ wall forces + damping_force_n
// (no coupling wall here). Local damping (Cundall 1987) is a force on each
// particle that no wall carries; with it in the balance every force is
// accounted for, so the balance closes to round-off. Without damping the
// monitor is zero and the same balance closes without it.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "dem_test_support.hpp"
#include "dfc/dem/dem_backend.hpp"

namespace dfc::dem {
namespace {

Vec3 vec(const nlohmann::json& a) { return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>()}; }

struct Balance {
  double residual = 0.0;  ///< largest |residual| / (|weight| + |pile force|) over the advances
  double damping = 0.0;   ///< largest |damping_force_n| on the same scale
  double damping_after_start = 0.0;  ///< largest |damping_force_n| once the pile moves, same scale
};

/// The balance over 40 advances of 50 steps of a pile pushed into the box
/// bed from step `start_step`, with `pile_damping` as pile.local_damping.
Balance momentum_balance(double local_damping, std::int64_t start_step = 0, std::optional<double> pile_damping = std::nullopt) {
  nlohmann::json c = test::box_bed_config();
  c["damping"]["local"] = local_damping;
  c["pile"] = {{"radius_m", 0.008}, {"tip_z_m", 0.03}, {"length_m", 0.03}, {"velocity_m_s", {0, 0, -0.2}}, {"start_step", start_step}};
  if (pile_damping) c["pile"]["local_damping"] = *pile_damping;
  DemBackend backend;
  const nlohmann::json info = backend.configure(c);
  const double dt = info["dt_suggested"].get<double>();
  const std::int64_t steps = 50;
  Vec3 weight;
  const ParticleStore& p = backend.simulation().particles();
  for (std::size_t i = 0; i < p.size(); ++i) weight += p.mass[i] * Vec3{0, 0, -9.81};
  Vec3 momentum = vec(backend.monitors()["particle_momentum_n_s"]);
  Balance balance;
  for (int exchange = 0; exchange < 40; ++exchange) {
    const nlohmann::json m = backend.advance({backend.simulation().step_count(), steps, dt, {}}).monitors;
    Vec3 walls;
    for (const char* wall : {"floor", "x0", "x1", "y0", "y1", "pile"}) walls += vec(m["wall_" + std::string(wall) + "_force_n"]);
    const Vec3 damping = vec(m["damping_force_n"]);
    const Vec3 next = vec(m["particle_momentum_n_s"]);
    const Vec3 rate = (1.0 / (double(steps) * dt)) * (next - momentum);
    momentum = next;
    const Vec3 residual = rate - (weight - walls + damping);
    const double scale = norm(weight) + std::abs(m["pile_force_n"].get<double>());
    balance.residual = std::max(balance.residual, norm(residual) / scale);
    balance.damping = std::max(balance.damping, norm(damping) / scale);
    if (backend.simulation().step_count() - steps >= start_step)
      balance.damping_after_start = std::max(balance.damping_after_start, norm(damping) / scale);
  }
  return balance;
}

TEST(MomentumBalance, WeightWallsAndDampingAccountForTheParticlesMomentumChange) {
  // Round-off only: the sums over 75 spheres and 50 steps of forces of the
  // size of the weight lose a few ulps each; 1e-9 leaves three decades.
  const Balance damped = momentum_balance(0.7);
  EXPECT_LT(damped.residual, 1e-9);
  EXPECT_GT(damped.damping, 1e-3);  // the damping term matters: without it the balance would not close
  const Balance undamped = momentum_balance(0.0);
  EXPECT_LT(undamped.residual, 1e-9);
  EXPECT_EQ(undamped.damping, 0.0);  // undamped: the damping force is zero, not left over
}

TEST(MomentumBalance, ThePilesOwnDampingTakesOverWhenItStartsMoving) {
  // pile.local_damping 0 from step 500 (the 11th advance) of a bed damped
  // at 0.7: damped before (the term matters, > 1e-3 of the scale), exactly
  // zero from the pile's first moving step, and the balance closes throughout.
  const Balance staged = momentum_balance(0.7, 500, 0.0);
  EXPECT_LT(staged.residual, 1e-9);
  EXPECT_GT(staged.damping, 1e-3);
  EXPECT_EQ(staged.damping_after_start, 0.0);
  // The same with the stage's damping equal to the bed's: nothing changes, bit for bit.
  EXPECT_EQ(momentum_balance(0.7, 500, 0.7).residual, momentum_balance(0.7, 500).residual);
}

}  // namespace
}  // namespace dfc::dem
