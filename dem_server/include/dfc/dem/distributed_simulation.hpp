#pragma once
// DistributedSimulation: one Simulation decomposed over the processes of an
// MPI communicator, with the same bits as the whole body on one process for
// any process count (docs/determinism.md; issue "Beyond one machine").
//
// Each process holds the particles of its box of a weighted recursive
// coordinate bisection (rcb_decomposition.hpp) and a halo: every particle
// within the search reach (2 r_max + skin) of the box, and every partner of a
// bond (intact or broken) of its own particles however far. It steps them all
// as a whole body (a local Simulation): a pair that crosses a boundary is
// computed on both sides from the same inputs, so no force is sent back
// (LAMMPS' "newton off"). After each step the owners send their particles'
// motion to the processes that hold them in a halo, and the Verlet test is
// made over the whole body (a max over processes, exact). When it calls for
// a rebuild, the body is decomposed again: every particle, with the history
// of its contacts and bonds (rows keyed by particle ids) and of its wall
// contacts, moves to the process that owns its position now.
//
// Why the bits match the whole body's: the local Simulation orders its slots
// canonically (neighbour_search.hpp), with the whole body's largest radius,
// so an owned particle meets all its partners in the order the whole body's
// lists give them, from inputs that are the same bits; its force and motion
// are then the same bits. Halo particles at the edge miss partners and go
// wrong, but their motion is overwritten by their owners' every step, and
// their pair history is never sent on (only rows with an owned particle are).
//
// Walls are held by every process and move alike; after each step their
// loads are the whole body's (gathered and summed in its contact order), and
// the monitors are exact sums over every process's own particles. A graded
// body's first step starts on the whole body (its seam balance solves over
// it), see step(). The experiments above reach it through DistributedEngine
// (distributed_engine.hpp). Not yet: periodic cells (refused) and
// checkpoints (docs/determinism.md §4).
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <mpi.h>

#include "dfc/common/state_archive.hpp"
#include "dfc/dem/exact_sum.hpp"
#include "dfc/dem/measurements.hpp"
#include "dfc/dem/rcb_decomposition.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

/// One particle as it travels between processes (plain bytes: the processes
/// of a run share one binary format).
struct ParticleRecord {
  std::int64_t id = 0;
  Vec3 position, velocity, angular_velocity, force, moment;
  double radius = 0.0, mass = 0.0, inertia = 0.0;
  std::int32_t owner = 0;  ///< rank that owns it after the decomposition
  std::uint16_t material = 0;
};

/// Appends `r` to `store` as a particle (its owner dropped).
void append_record(ParticleStore& store, const ParticleRecord& r);

/// What the last decomposition and the steps since moved (benchmarks, tests).
struct DecompositionStats {
  std::size_t decompositions = 0;
  std::size_t recuts = 0;           ///< decompositions that cut the boxes anew (the others kept the last cuts: the load had not drifted)
  std::size_t owned = 0;            ///< particles this process owns
  std::size_t halo = 0;             ///< particles it holds for others
  std::size_t migrated = 0;         ///< owned particles that came from another process at the last decomposition
  std::size_t halo_bytes_per_step = 0;  ///< bytes this process sends after each step
  double step_seconds = 0.0;       ///< wall time in the local steps
  double halo_seconds = 0.0;       ///< wall time in the halo updates and the Verlet test (waits for the others included)
  double decompose_seconds = 0.0;  ///< wall time in the decompositions
};

class DistributedSimulation {
 public:
  /// `local`: built with the same settings, walls and set-up calls on every
  /// process of `comm` (e.g. install_bonds_now); on rank 0 it holds the whole
  /// body (with any seeded pair history, or stepped: its lists' history is
  /// sent), on the others either no particles or the same body built and
  /// stepped alike (then dropped at the first decomposition: a generation
  /// or a seam balance, which solves over the whole body, runs on every
  /// process as on one). Not periodic (UserError). `local` must outlive this
  /// object and is stepped only through it.
  DistributedSimulation(MPI_Comm comm, Simulation& local);
  ~DistributedSimulation();
  DistributedSimulation(const DistributedSimulation&) = delete;
  DistributedSimulation& operator=(const DistributedSimulation&) = delete;

  /// One step of dt on every process (collective). A rebuild the whole
  /// body's Verlet test calls for, a decomposition, is taken at the start of
  /// the next step. An error on any process
  /// (an unstable step: SolverError) is thrown on every one, with the
  /// message of the lowest that failed. Afterwards every
  /// process's walls carry the whole body's forces, moments and vertex
  /// forces, summed in the whole body's contact order (the same bits);
  /// `record` as Simulation::step (the pairs' outputs, which no whole-body
  /// sum reads yet).
  void step(double dt, ContactRecord record = ContactRecord::complete);
  /// Decomposes the body again before the next step, as a rebuild due would
  /// (benchmarks: the cost of a decomposition; call it on every process).
  void request_rebuild() noexcept { rebuild_requested_ = true; }
  /// s, the whole body's critical time step (collective).
  [[nodiscard]] double critical_timestep() const;

  [[nodiscard]] int rank() const noexcept { return rank_; }
  [[nodiscard]] int ranks() const noexcept { return ranks_; }
  [[nodiscard]] const Simulation& local() const noexcept { return local_; }
  /// Whether slot `slot` of local().particles() is this process's own.
  [[nodiscard]] bool owns(std::size_t slot) const { return owned_.at(slot) != 0; }
  /// Per slot of local().particles(): 1 where this process owns it (before
  /// the first decomposition rank 0 owns every particle).
  [[nodiscard]] std::span<const std::uint8_t> owned_slots() const noexcept { return owned_; }
  [[nodiscard]] const DecompositionStats& stats() const noexcept { return stats_; }

  /// Every owned particle of every process, by id, on `root` (empty on the
  /// others; collective).
  [[nodiscard]] std::vector<ParticleRecord> gather_particles(int root = 0) const;
  /// Bonds by state over the whole body (each pair counted by the owner of
  /// its first particle; collective).
  [[nodiscard]] BondCounts bond_counts() const;
  /// measure() of the whole body, to its bits: each process's exact sums
  /// over its own particles and contacts, added by their limbs (collective).
  [[nodiscard]] Measurements measure() const;
  /// N s, Simulation::momentum of the whole body, to its bits (collective).
  [[nodiscard]] Vec3 momentum() const;
  /// Replaces every process's partial `sums` by their exact total (their limbs added; collective).
  void sum_over_processes(std::span<ExactSum> sums) const;
  /// The whole body's state as Simulation::save_state of the body on one
  /// process writes it, into `out` on rank 0 (nothing elsewhere; collective):
  /// the particles gathered by id, their lists rebuilt where the whole body's
  /// last rebuild built them (replace_body_at_references), so a checkpoint
  /// that any process count restores (each process loads it whole; the first
  /// decomposition cuts it where its last rebuild saw it).
  void save_whole_body(StateWriter& out);
  /// Every process's `values` one after the other in rank order, on every process (collective).
  [[nodiscard]] std::vector<double> gather_over_processes(std::span<const double> values) const;
  /// Every process's `values` one after the other in rank order, on `root` (empty elsewhere; collective).
  [[nodiscard]] std::vector<double> gather_on_root(std::span<const double> values, int root = 0) const;

 private:
  /// Decomposes the body anew and moves particles and history (collective).
  void decompose();
  /// The first decomposition: what must be taken on the whole body first
  /// (a seam balance), and a body with lists already built cut where its
  /// last rebuild saw it (Simulation::move_to_references; collective).
  void first_decomposition(double dt);
  /// Sends the owners' motion to the halos (collective).
  void update_halo();
  /// The whole body's Verlet test (collective).
  [[nodiscard]] bool lists_used_up() const;
  /// Runs `work` on every process; if it throws on any, throws the same kind
  /// of error with the lowest failing process's message on all (collective).
  void collectively(const std::function<void()>& work) const;
  /// Gathers the owned particles' wall contacts of every process and sums
  /// them into every process's walls in the whole body's order (collective).
  void update_wall_forces();

  MPI_Comm comm_;
  Simulation& local_;
  int rank_ = 0, ranks_ = 1;
  std::vector<std::uint8_t> owned_;  ///< per local slot
  /// Per local slot: the cell (z, y, x) of the lattice its slot is sorted by
  /// at the last rebuild; with the id, its place in the whole body's slot order.
  std::vector<std::array<std::int64_t, 3>> cell_;
  /// Per rank: the local slots whose motion goes to it after each step, and
  /// the local slots that take the motion it sends, in the same order.
  std::vector<std::vector<std::uint32_t>> send_slots_, receive_slots_;
  bool decomposed_ = false;
  bool rebuild_requested_ = false;
  std::optional<RcbDecomposition> rcb_;  ///< the boxes of the last decomposition
  struct Buffers;
  std::unique_ptr<Buffers> buffers_;  ///< a decomposition's exchange buffers, kept for the next
  DecompositionStats stats_;
};

}  // namespace dfc::dem
