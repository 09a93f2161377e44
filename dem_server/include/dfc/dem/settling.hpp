#pragma once
// Running a packing until it is in equilibrium: the unbalanced-force ratio
// (measurements.hpp) at most a target, checked every check_every steps, after
// at least min_steps. The stop of a generation stage that has no servo: a body
// settling under N g (conventional_generation.hpp), or a generated body's
// equilibration outside a coupled run (the coupled run stops on the same
// ratio through run.stop_when, checked at every exchange).
#include <cstdint>
#include <functional>

#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

struct SettlingTarget {
  double unbalanced_force_ratio = 0.002;
  std::int64_t check_every = 10;     ///< steps (the coupled runs' exchange interval)
  std::int64_t min_steps = 200;      ///< before the first check counts (a run.stop_when's min_exchanges)
  std::int64_t max_steps = 2000000;
  /// Called at every check (steps so far, ratio): progress for a long run; may be empty.
  std::function<void(std::int64_t, double)> on_check;
};

struct Settling {
  bool reached = false;
  std::int64_t steps = 0;
  double ratio = 0.0;  ///< at the last check
};

/// Steps `simulation` at dt until `target` is met or max_steps were taken.
/// The steps between checks record only the gathered contact outputs.
[[nodiscard]] Settling settle(Simulation& simulation, double dt, const SettlingTarget& target);

}  // namespace dfc::dem
