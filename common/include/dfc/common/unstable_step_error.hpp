#pragma once
// UnstableStepError: a solver refuses a time step above its stability limit
// before it runs anything (SPEC.md §5.2, §7): the reply carries the largest
// stable step as a number, and the session keeps its state and step, so the
// client can retry with dt <= dt_max. Every other SolverError is fatal.
#include <string>

#include "dfc/common/errors.hpp"

namespace dfc {

class UnstableStepError : public SolverError {
 public:
  UnstableStepError(const std::string& message, double dt_max) : SolverError(message), dt_max_(dt_max) {}
  /// s, the largest step the solver can run stably now.
  [[nodiscard]] double dt_max() const noexcept { return dt_max_; }

 private:
  double dt_max_;
};

}  // namespace dfc
