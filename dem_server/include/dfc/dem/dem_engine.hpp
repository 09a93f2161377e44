#pragma once
// DemEngine: the DEM core as the experiments above it see it (the loading
// protocols, DemBackend's advance, monitors and snapshots): one body stepped
// as a whole, whether it lives in one process (LocalEngine) or is decomposed
// over the processes of an MPI run (DistributedEngine, dfc_dem_mpi;
// docs/determinism.md §3). Both give the same bits: every whole-body
// quantity is an exact sum (exact_sum.hpp), a max or a gather by id, never a
// sum whose rounding depends on which process held which term.
//
// The split (issue "Beyond one machine", after LAMMPS' Domain/Comm above its
// pair styles): part() is this process's Simulation. Its walls, settings and
// step count are the whole body's on every process (each process moves them
// alike; a wall's loads after a step are the whole body's sums); its
// particles are this process's own and its halo. Whatever reads particles
// for the whole body goes through the engine: the measures below, or the
// collectives (sum, max, gather) over the slots owned() marks. Every process
// makes the same calls in the same order (the experiments run replicated),
// so a collective never waits for a process that does not come.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "dfc/common/state_archive.hpp"
#include "dfc/dem/exact_sum.hpp"
#include "dfc/dem/measurements.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

class DemEngine {
 public:
  virtual ~DemEngine() = default;

  /// This process's part of the body (all of it on one process).
  [[nodiscard]] virtual Simulation& part() noexcept = 0;
  [[nodiscard]] virtual const Simulation& part() const noexcept = 0;
  /// The processes the body is decomposed over, and this one's rank (0 speaks for the run).
  [[nodiscard]] virtual int processes() const noexcept { return 1; }
  [[nodiscard]] virtual int rank() const noexcept { return 0; }

  /// One step of dt of the whole body (collective); an error on any process is thrown on all.
  virtual void step(double dt, ContactRecord record) = 0;
  /// s, the whole body's critical time step (collective).
  [[nodiscard]] virtual double critical_timestep() const = 0;
  /// measure() of the whole body, to its bits (collective).
  [[nodiscard]] virtual Measurements measure() const = 0;
  /// N s, the whole body's momentum (collective).
  [[nodiscard]] virtual Vec3 momentum() const = 0;
  /// Bonds by state over the whole body (collective).
  [[nodiscard]] virtual BondCounts bond_counts() const = 0;

  /// Per slot of part().particles(): whether this process counts it as its
  /// own (empty: every slot is, one process).
  [[nodiscard]] virtual std::span<const std::uint8_t> owned() const = 0;
  /// Replaces each of `sums` (this process's partial sums) by the whole
  /// body's: the partial sums of every process added exactly (collective).
  virtual void sum_over_processes(std::span<ExactSum> sums) const = 0;
  /// The largest of every process's `value` (collective).
  [[nodiscard]] virtual double max_over_processes(double value) const = 0;
  /// Every process's `values` one after the other in rank order, on every
  /// process (collective). A caller that needs an order sorts them.
  [[nodiscard]] virtual std::vector<double> gather_over_processes(std::span<const double> values) const = 0;
  /// Every process's `values` one after the other in rank order, on rank 0
  /// (empty elsewhere; collective): rows of a snapshot, which only rank 0 writes.
  [[nodiscard]] virtual std::vector<double> gather_on_root(std::span<const double> values) const = 0;
  /// The whole body's particles ordered by id, on rank 0 (empty elsewhere;
  /// collective).
  [[nodiscard]] virtual ParticleStore whole_body_by_id() const = 0;
  /// The whole body's Simulation::save_state into `out` on rank 0 (nothing
  /// elsewhere; collective): the bytes the body on one process writes, which
  /// any process count restores (a checkpoint; docs/determinism.md §3).
  virtual void save_whole_body(StateWriter& out) = 0;

  /// Whether slot `i` is this process's (see owned()).
  [[nodiscard]] bool owns(std::size_t i) const {
    const auto mask = owned();
    return mask.empty() || mask[i] != 0;
  }
};

/// The body in one process: part() is the whole Simulation, the collectives are identities.
class LocalEngine final : public DemEngine {
 public:
  explicit LocalEngine(Simulation& simulation) : simulation_(simulation) {}
  [[nodiscard]] Simulation& part() noexcept override { return simulation_; }
  [[nodiscard]] const Simulation& part() const noexcept override { return simulation_; }
  void step(double dt, ContactRecord record) override { simulation_.step(dt, record); }
  [[nodiscard]] double critical_timestep() const override { return simulation_.critical_timestep(); }
  [[nodiscard]] Measurements measure() const override;
  [[nodiscard]] Vec3 momentum() const override { return simulation_.momentum(); }
  [[nodiscard]] BondCounts bond_counts() const override { return simulation_.bond_counts(); }
  [[nodiscard]] std::span<const std::uint8_t> owned() const override { return {}; }
  void sum_over_processes(std::span<ExactSum> /*sums*/) const override {}
  [[nodiscard]] double max_over_processes(double value) const override { return value; }
  [[nodiscard]] std::vector<double> gather_over_processes(std::span<const double> values) const override {
    return {values.begin(), values.end()};
  }
  [[nodiscard]] std::vector<double> gather_on_root(std::span<const double> values) const override { return {values.begin(), values.end()}; }
  [[nodiscard]] ParticleStore whole_body_by_id() const override;
  void save_whole_body(StateWriter& out) override { simulation_.save_state(out); }

 private:
  Simulation& simulation_;
};

/// Makes the engine of a built model's simulation (DemBackend: a LocalEngine,
/// or under MPI a DistributedEngine over the run's processes).
using EngineFactory = std::unique_ptr<DemEngine> (*)(Simulation& simulation);
[[nodiscard]] std::unique_ptr<DemEngine> make_local_engine(Simulation& simulation);

/// The exact sums of N terms over the slots the engine owns, added over
/// every process (collective): terms(i) gives slot i's N terms.
template <std::size_t N, class Terms>
[[nodiscard]] std::array<ExactSum, N> body_accumulators(const DemEngine& engine, const Terms& terms) {
  const Simulation& s = engine.part();
  const auto owned = engine.owned();
  std::array<ExactSum, N> sums = exact_accumulators<N>(s.particles().size(), s.threads(), [&](std::size_t i) {
    return owned.empty() || owned[i] ? terms(i) : std::array<double, N>{};
  });
  engine.sum_over_processes(sums);
  return sums;
}

}  // namespace dfc::dem
