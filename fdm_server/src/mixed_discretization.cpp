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

void apply_mean_stress_mixed_discretization(std::span<SymTensor> stresses, std::span<const double> old_means,
                                            std::span<const double> volumes) {
  assert(stresses.size() == volumes.size() && old_means.size() == volumes.size());
  double weighted_increment = 0.0;
  double total_volume = 0.0;
  for (std::size_t t = 0; t < stresses.size(); ++t) {
    weighted_increment += (stresses[t].trace() / 3.0 - old_means[t]) * volumes[t];
    total_volume += volumes[t];
  }
  const double zone_increment = weighted_increment / total_volume;
  for (std::size_t t = 0; t < stresses.size(); ++t) {
    const double correction = zone_increment - (stresses[t].trace() / 3.0 - old_means[t]);
    stresses[t].xx += correction;
    stresses[t].yy += correction;
    stresses[t].zz += correction;
  }
}

}  // namespace dfc::fdm
