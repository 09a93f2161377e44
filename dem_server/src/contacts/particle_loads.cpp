#include "dfc/dem/particle_loads.hpp"

#include "dfc/dem/parallel.hpp"

namespace dfc::dem {

void start_particle_loads(ParticleStore& p, const Vec3& gravity, int threads) {
  const auto n = static_cast<std::int64_t>(p.size());
#pragma omp parallel for schedule(static) num_threads(threads) if(n >= min_parallel_items)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = std::size_t(ii);
    p.force[i] = p.mass[i] * gravity;
    p.moment[i] = Vec3{};
  }
}

}  // namespace dfc::dem
