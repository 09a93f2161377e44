// The main thread's work counter (dfc::work_progress, SPEC.md §9.1, protocol
// 1.8): a DEM step and a neighbour-list rebuild move it, so that the
// heartbeat's pongs show a server that works, however long its advance.
#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/common/work_progress.hpp"

namespace dfc::dem {
namespace {

TEST(WorkProgress, EveryStepAndEveryRebuildMoveTheCounter) {
  Simulation sim = test::undamped(test::linear(1e5, 1e4, 0.5));
  sim.add_sphere(1, {0, 0, 0}, 1e-3, 2650.0);
  sim.add_sphere(2, {3e-3, 0, 0}, 1e-3, 2650.0);
  sim.step(1e-6);  // the first step rebuilds: from here on steps alone

  std::int64_t before = work_progress::current();
  for (int s = 0; s < 10; ++s) sim.step(1e-6);
  EXPECT_GE(work_progress::current() - before, 10);  // one per step at least

  sim.request_rebuild();
  before = work_progress::current();
  sim.step(1e-6);
  EXPECT_GE(work_progress::current() - before, 2);  // the rebuild's and the step's
}

TEST(WorkProgress, ALongLoopMovesTheCounterOnceEveryStride) {
  const std::int64_t before = work_progress::current();
  for (std::int64_t i = 0; i < 10'000; ++i) work_progress::advance_every(i, 1024);
  EXPECT_EQ(work_progress::current() - before, 10);  // at 0, 1024, ..., 9216
}

}  // namespace
}  // namespace dfc::dem
