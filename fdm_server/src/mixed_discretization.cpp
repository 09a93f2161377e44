#include "dfc/fdm/mixed_discretization.hpp"

#include <cassert>

namespace dfc::fdm {

void apply_mixed_discretization(std::span<SymTensor> strain_rates, std::span<const double> volumes) {
  assert(strain_rates.size() == volumes.size());
  double weighted_trace = 0.0;
  double total_volume = 0.0;
  for (std::size_t t = 0; t < strain_rates.size(); ++t) {
    weighted_trace += strain_rates[t].trace() * volumes[t];
    total_volume += volumes[t];
  }
  const double zone_trace = weighted_trace / total_volume;
  for (SymTensor& rate : strain_rates) {
    const double correction = (zone_trace - rate.trace()) / 3.0;
    rate.xx += correction;
    rate.yy += correction;
    rate.zz += correction;
  }
}

}  // namespace dfc::fdm
