#include "dfc/dem/stress_scaling.hpp"

#include <algorithm>
#include <limits>

#include "dfc/dem/bond_state.hpp"

namespace dfc::dem {

StressScalingReport scale_to_profile(ReplicatedBody& body, const std::vector<HistoryColumn>& columns, const StressProfile& profile,
                                     double reference_vertical) {
  std::vector<std::size_t> dimensional;
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c].unit != "-") dimensional.push_back(c);
  StressScalingReport report{.lambda_min = std::numeric_limits<double>::infinity(), .lambda_max = -std::numeric_limits<double>::infinity()};
  for (std::size_t k = 0; k < body.pairs.size(); ++k) {
    double* row = body.rows.data() + k * body.stride;
    if (bond_state(row) != BondState::intact) {
      ++report.other_rows;
      continue;
    }
    const GeneratedSphere& a = body.spheres[body.pairs[k][0]];
    const GeneratedSphere& b = body.spheres[body.pairs[k][1]];
    // The contact point divides the centre line in the ratio of the radii.
    const double z_contact = a.centre.z + (b.centre.z - a.centre.z) * a.radius / (a.radius + b.radius);
    const double lambda = profile.vertical(z_contact) / reference_vertical;
    for (const std::size_t c : dimensional) row[c] *= lambda;
    ++report.scaled_bonds;
    report.lambda_min = std::min(report.lambda_min, lambda);
    report.lambda_max = std::max(report.lambda_max, lambda);
  }
  if (report.scaled_bonds == 0) report.lambda_min = report.lambda_max = 0.0;
  return report;
}

}  // namespace dfc::dem
