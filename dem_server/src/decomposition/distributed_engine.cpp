#include "dfc/dem/distributed_engine.hpp"

#include <vector>

namespace dfc::dem {

double DistributedEngine::max_over_processes(double value) const {
  double body = value;
  MPI_Allreduce(&value, &body, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return body;
}

ParticleStore DistributedEngine::whole_body_by_id() const {
  ParticleStore body;
  for (const ParticleRecord& r : body_.gather_particles(0)) append_record(body, r);
  return body;
}

std::unique_ptr<DemEngine> make_world_engine(Simulation& simulation) { return std::make_unique<DistributedEngine>(MPI_COMM_WORLD, simulation); }

}  // namespace dfc::dem
