#include <algorithm>
#include <numeric>

#include "dfc/dem/dem_engine.hpp"

namespace dfc::dem {

Measurements LocalEngine::measure() const { return dfc::dem::measure(simulation_); }

ParticleStore LocalEngine::whole_body_by_id() const {
  ParticleStore body = simulation_.particles();
  std::vector<std::uint32_t> by_id(body.size());
  std::iota(by_id.begin(), by_id.end(), 0U);
  std::sort(by_id.begin(), by_id.end(), [&](std::uint32_t a, std::uint32_t b) { return body.id[a] < body.id[b]; });
  body.permute(by_id, simulation_.threads());
  return body;
}

std::unique_ptr<DemEngine> make_local_engine(Simulation& simulation) { return std::make_unique<LocalEngine>(simulation); }

}  // namespace dfc::dem
