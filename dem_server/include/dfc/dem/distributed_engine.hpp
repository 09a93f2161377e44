#pragma once
// DistributedEngine: the DemEngine of a body decomposed over the processes
// of an MPI communicator (distributed_simulation.hpp), so that the loading
// protocols and DemBackend run on it unchanged (dem_engine.hpp): every
// process runs them alike, and their whole-body reads are the collectives
// below. The same bits as a LocalEngine over the whole body, for any
// process count (docs/determinism.md §3).
#include <memory>

#include <mpi.h>

#include "dfc/dem/dem_engine.hpp"
#include "dfc/dem/distributed_simulation.hpp"

namespace dfc::dem {

class DistributedEngine final : public DemEngine {
 public:
  /// `local`: the whole body, built alike on every process of `comm` (see DistributedSimulation); it must outlive the engine.
  DistributedEngine(MPI_Comm comm, Simulation& local) : comm_(comm), local_(local), body_(comm, local) {}

  [[nodiscard]] Simulation& part() noexcept override { return local_; }
  [[nodiscard]] const Simulation& part() const noexcept override { return local_; }
  [[nodiscard]] int processes() const noexcept override { return body_.ranks(); }
  [[nodiscard]] int rank() const noexcept override { return body_.rank(); }

  void step(double dt, ContactRecord record) override { body_.step(dt, record); }
  [[nodiscard]] double critical_timestep() const override { return body_.critical_timestep(); }
  [[nodiscard]] Measurements measure() const override { return body_.measure(); }
  [[nodiscard]] Vec3 momentum() const override { return body_.momentum(); }
  [[nodiscard]] BondCounts bond_counts() const override { return body_.bond_counts(); }

  [[nodiscard]] std::span<const std::uint8_t> owned() const override { return body_.owned_slots(); }
  void sum_over_processes(std::span<ExactSum> sums) const override { body_.sum_over_processes(sums); }
  [[nodiscard]] double max_over_processes(double value) const override;
  [[nodiscard]] std::vector<double> gather_over_processes(std::span<const double> values) const override {
    return body_.gather_over_processes(values);
  }
  [[nodiscard]] std::vector<double> gather_on_root(std::span<const double> values) const override { return body_.gather_on_root(values); }
  [[nodiscard]] ParticleStore whole_body_by_id() const override;
  void save_whole_body(StateWriter& out) override { body_.save_whole_body(out); }

  /// The decomposition (benchmarks, tests).
  [[nodiscard]] const DistributedSimulation& decomposed() const noexcept { return body_; }

 private:
  MPI_Comm comm_;
  Simulation& local_;
  DistributedSimulation body_;
};

/// A DistributedEngine over MPI_COMM_WORLD (DemBackend's engine factory under dem_server --mpi).
[[nodiscard]] std::unique_ptr<DemEngine> make_world_engine(Simulation& simulation);

}  // namespace dfc::dem
