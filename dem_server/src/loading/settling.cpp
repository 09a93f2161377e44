#include "dfc/dem/settling.hpp"

#include "dfc/dem/measurements.hpp"

namespace dfc::dem {

Settling settle(Simulation& sim, double dt, const SettlingTarget& target) {
  Settling out;
  while (out.steps < target.max_steps) {
    const bool check = (out.steps + 1) % target.check_every == 0 && out.steps + 1 >= target.min_steps;
    const bool last = out.steps + 1 == target.max_steps;
    sim.step(dt, check || last ? ContactRecord::complete : ContactRecord::gathered_only);
    ++out.steps;
    if (!check) continue;
    out.ratio = measure(sim).unbalanced_force_ratio;
    if (target.on_check) target.on_check(out.steps, out.ratio);
    if (out.ratio <= target.unbalanced_force_ratio) {
      out.reached = true;
      break;
    }
  }
  return out;
}

}  // namespace dfc::dem
