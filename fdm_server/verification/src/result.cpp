#include "dfc/fdm/verification/result.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dfc::fdm::verification {

VerificationRow compare(std::string quantity, std::string unit, double computed, double closed_form, double tolerance, double scale) {
  VerificationRow row;
  row.quantity = std::move(quantity);
  row.unit = std::move(unit);
  row.computed = computed;
  row.closed_form = closed_form;
  row.tolerance = tolerance;
  const double reference = scale > 0.0 ? scale : std::abs(closed_form);
  // A non-finite result must fail, whatever the comparison would say.
  row.error = std::isfinite(computed) ? std::abs(computed - closed_form) / reference : std::numeric_limits<double>::infinity();
  return row;
}

bool ProblemResult::passed() const {
  return !rows.empty() && std::all_of(rows.begin(), rows.end(), [](const VerificationRow& r) { return r.passed(); });
}

double ProblemResult::worst_error_ratio() const {
  double worst = 0.0;
  for (const VerificationRow& r : rows) worst = std::max(worst, r.error / r.tolerance);
  return worst;
}

}  // namespace dfc::fdm::verification
