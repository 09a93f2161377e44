#pragma once
// Simulation: particles, walls, contact lists and the time step loop of the DEM.
//
// One step (PFC cycle, Itasca PFC "Calculation Cycle"):
//   1. rebuild the candidate lists if the Verlet skin is used up;
//   2. contact forces: every particle pair and particle–facet candidate,
//      in parallel into per-contact storage, the law chosen once per step;
//      the pair loop also adds most contacts to the particles' resultants,
//      which start from gravity (contact_lists.hpp Incidence);
//   3. law of motion: per particle, add the remaining contact forces in the
//      same fixed order, apply local damping, advance velocities and positions;
//   4. walls: distribute the contact forces to facet vertices, then move the
//      vertices with their velocities.
// The same input and thread count give the same result bit for bit, and so
// does any other thread count (no sum depends on how work is split).
//
// Bonds (bonded particle laws, bond_state.hpp): at the first rebuild every
// pair whose surface gap is at most the law's bond_gap is bonded. From then
// on every pair that was ever bonded stays in the pair list at every rebuild
// (the persistent bond list), so a bond keeps its history however far its
// particles separate before it breaks, and broken bonds stay counted. A
// sample prepared unbonded (radius expansion, then a servo, as PFC does)
// sets install_bonds_at_start = false and calls install_bonds_now() when ready.
//
// Periodic cell (periodic_cell.hpp, docs/dem_periodic.md): with one set,
// branch vectors are minimum images, particles are wrapped into the cell at
// every rebuild (history and bonds are keyed by particle ids, so they survive
// the wrap), and each step ends with the cell's affine deformation.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <unordered_set>
#include <vector>

#include "dfc/common/sections/dem_sections.hpp"
#include "dfc/dem/bond_state.hpp"
#include "dfc/dem/contact_law_registry.hpp"
#include "dfc/dem/contact_lists.hpp"
#include "dfc/dem/particle_materials.hpp"
#include "dfc/dem/neighbour_search.hpp"
#include "dfc/dem/particle_store.hpp"
#include "dfc/dem/periodic_cell.hpp"
#include "dfc/dem/seam_balance.hpp"
#include "dfc/dem/timestep.hpp"
#include "dfc/dem/wall.hpp"

namespace dfc {
class StateWriter;
class StateReader;
}  // namespace dfc

namespace dfc::dem {

struct SimulationSettings {
  ContactLawSetting particle_law;  ///< particle–particle contacts (material 0)
  Vec3 gravity;                    ///< m/s^2 (already N g in a centrifuge)
  double local_damping = sections::kDefaultLocalDamping;  ///< alpha of local damping, [0, 1)
  double skin = 0.0;               ///< m, Verlet skin; <= 0: 0.2 x the largest radius
  int threads = 0;                 ///< OpenMP threads; <= 0: the OpenMP default
  bool install_bonds_at_start = true;  ///< bonded laws: bond at the first rebuild (false: wait for install_bonds_now)
  /// A step throws SolverError when a contact overlap exceeds this fraction of
  /// the smaller radius (a wall contact: of the particle's): the sign of an
  /// unstable run (dem.timestep.max_overlap_fraction).
  double max_overlap_fraction = sections::kDefaultMaxOverlapFraction;
  /// Laws of particle materials 1, 2, ... (graded upscaling: a zone each;
  /// particle_materials.hpp): the same law as particle_law, other parameters.
  std::vector<ContactLawSetting> material_laws{};
  /// Which radius each sphere's stiffness bound is taken at (timestep.hpp;
  /// dem.timestep.stiffness_bound).
  StepBound step_bound = StepBound::per_particle;
};

class Simulation {
 public:
  explicit Simulation(SimulationSettings settings);

  // Set-up --------------------------------------------------------------------
  /// Adds a solid sphere at rest. Ids must be unique and the material one of
  /// the settings' (UserError otherwise).
  void add_sphere(std::int64_t id, Vec3 centre, double radius, double density, MaterialId material = 0);
  /// Direct access to the particle arrays (e.g. to set velocities); the
  /// neighbour lists are rebuilt before the next step.
  [[nodiscard]] ParticleStore& particles_for_edit();
  /// The particle arrays for a change of positions, velocities and spins
  /// alone (a decomposed run's halo update): the lists and the critical step stay.
  [[nodiscard]] ParticleStore& particle_motion_for_edit() noexcept { return particles_; }
  /// Returns the wall's index.
  std::size_t add_wall(Wall wall);
  /// Replaces a wall (e.g. a new interface mesh); its contact history is dropped.
  void replace_wall(std::size_t index, Wall wall);
  /// Velocities of a coupling wall's vertices for the following steps.
  void set_vertex_velocities(std::size_t wall, std::span<const Vec3> velocity);
  /// Translation velocity of a prescribed (rigid) wall from the next step on,
  /// e.g. set by a servo; UserError for a coupling wall.
  void set_wall_velocity(std::size_t wall, const Vec3& velocity);

  // Running -------------------------------------------------------------------
  /// s, see timestep.hpp; kept until particles, radii or walls change (the
  /// servers check every advance against it: an O(N) pass over the laws).
  [[nodiscard]] double critical_timestep() const;
  /// One step of dt, without checking dt against the critical step.
  /// record = gathered_only when nothing reads contact_outputs() before the
  /// next step (a step in the middle of a run): faster, same motion.
  void step(double dt, ContactRecord record = ContactRecord::complete);
  /// The start of step(dt) before any force: the rebuild due, the prescribed
  /// walls' velocities, a requested seam balance. step() calls it; a
  /// decomposed body calls it on the whole body first, where the seam balance
  /// solves over the whole body (distributed_simulation.hpp), and then steps.
  void prepare_step(double dt);
  /// The next rebuild searches at least as far as the last one did, so that
  /// it takes the same grid and the same canonical order (a decomposed body's
  /// parts after a rebuild that searched to the bonding gap).
  void repeat_last_search() noexcept { repeat_search_ = last_search_; }
  /// Where the particles (by id) and the walls are, and the Verlet
  /// bookkeeping of the walls' travel since the last rebuild.
  struct Places {
    std::vector<std::int64_t> id;  ///< increasing
    std::vector<Vec3> position;    ///< m, of id[k]
    std::vector<std::vector<Vec3>> wall_vertices;
    double wall_travel = 0.0, affine_approach = 0.0;
  };
  /// Puts every particle and wall back where the last rebuild saw them (its
  /// reference positions and vertices) and asks the next rebuild to search as
  /// far as it did: that rebuild then makes the lists the last one made (the
  /// same pairs, grid and canonical order). Returns the places to put back
  /// after it (put_back). A stepped body decomposed over processes takes its
  /// first decomposition so, and its bits do not change.
  [[nodiscard]] Places move_to_references();
  /// Where everything is now (see Places).
  [[nodiscard]] Places places() const;
  /// After the rebuild that followed move_to_references: every particle
  /// (found by id in `places`) and wall back at `places`, with the walls'
  /// travel and the affine approach since the last rebuild; the reference
  /// positions stay those of the rebuild.
  void put_back(const Places& places);
  /// Whether the next step rebuilds the lists.
  [[nodiscard]] bool lists_stale() const noexcept { return stale_; }
  /// Replaces the body by `at_reference` (every particle at its reference
  /// position of the last rebuild, the rest of its state as it is now) with
  /// the history rows of its pairs and wall contacts (keyed by ids), and
  /// rebuilds the lists there with the walls at their reference vertices and
  /// the last rebuild's search radius; then puts the particles and walls at
  /// `now`. The lists, slots and Verlet state are then those of a body that
  /// was never cut: a body decomposed over processes, gathered on one for its
  /// checkpoint (distributed_simulation.hpp). `rebuilds`: the count to keep.
  void replace_body_at_references(ParticleStore at_reference, HistoryArchive pairs, std::vector<HistoryArchive> wall_rows, const Places& now,
                                  std::size_t rebuilds);
  /// `steps` steps of dt; refuses dt > critical_timestep() with SolverError.
  /// Contact outputs are complete after the last step.
  void run(std::int64_t steps, double dt);
  /// Forces a neighbour-list rebuild before the next step.
  void request_rebuild() noexcept { stale_ = true; }
  /// Bonded laws: bonds every pair within the bond gap at the next rebuild
  /// (forced now); no effect once bonds were installed.
  void install_bonds_now() noexcept;
  /// Bonded laws: at the next rebuild (forced now), bonds every pair of
  /// particles of different materials within their pair law's bond gap
  /// whose history is empty (the seams between the zones of a graded
  /// generated body, whose pairs no REV held); then, before that step's
  /// forces, balances the seam (seam_balance.hpp) for laws that can take a
  /// load onto a bond. Meant for the start, when nothing moves.
  void bond_across_materials_now() noexcept;
  /// Whether the next step balances the seams (bond_across_materials_now): a
  /// solve over the whole body, which a decomposed body takes before its first decomposition.
  [[nodiscard]] bool seam_balance_pending() const noexcept { return join_materials_requested_; }
  /// What the last seam balance did (zero before one).
  [[nodiscard]] const SeamBalanceReport& seam_balance_report() const noexcept { return seam_report_; }
  /// Pair history (rows of particle_law's layout, keyed by particle ids) that
  /// the next rebuild restores instead of the current lists' history: a body
  /// built from a prepared one (PCRM replication, pcrm_replication.hpp) starts
  /// with its contacts' and bonds' state. Bonded rows stay pairs at every
  /// rebuild like installed bonds; with `bonds_installed` no gap-based
  /// installation follows. Every key must name particles that exist.
  void seed_pair_history(HistoryArchive archive, bool bonds_installed);
  /// Removes the particles for which `remove(slot)` is true, with their pair
  /// history, before the first step (UserError after it): e.g. generated
  /// spheres that a coupling wall, known only later, cuts. Returns how many.
  std::size_t remove_particles_before_start(const std::function<bool(std::size_t slot)>& remove);
  // A part of a decomposed body (distributed_simulation.hpp) -----------------
  // A process of a decomposed run holds its own particles and a halo of its
  // neighbours'. It steps them all like a whole body; these calls let the
  // decomposition keep its part's lists those of the whole body.
  /// The whole body's largest radius (m) and extent, as every process has
  /// them: the skin and the cell size of the next rebuild are the whole
  /// body's, so every part orders its particles on the same lattice
  /// (neighbour_search.hpp). Open space only (no periodic cell).
  void set_body_extent(double largest_radius, const BodyBounds& bounds) noexcept {
    body_r_max_ = largest_radius;
    body_bounds_ = bounds;
  }
  /// m, how far apart the centres of two candidates of the next rebuild can
  /// be: 2 r_max + the search distance (the skin, or the bonding gap while
  /// bonds are installed). A part's halo must be at least this wide.
  [[nodiscard]] double next_search_reach() const;
  /// Replaces every particle and the pair and wall history (rows keyed as
  /// archive_history keys them; walls: one archive per wall, in order) and
  /// forces a rebuild; step counter, walls, bonds-installed flag and
  /// requests stay. Keys must name particles that exist.
  void replace_body(ParticleStore particles, HistoryArchive pairs, std::vector<HistoryArchive> wall_rows);
  /// seed_pair_history()'s rows until the next rebuild takes them.
  [[nodiscard]] const std::optional<HistoryArchive>& seeded_pair_history() const noexcept { return seeded_pairs_; }
  /// Rebuilds the lists now if the next step would (so slots are final).
  void rebuild_if_stale();
  /// Particle positions at the last rebuild, by slot (the Verlet references).
  [[nodiscard]] std::span<const Vec3> reference_positions() const noexcept { return reference_positions_; }
  /// Whether a particle that moved `max_particle_displacement` m since the
  /// last rebuild used up the Verlet skin (with the walls' and the cell's
  /// motion): the test each step makes over its own particles.
  [[nodiscard]] bool verlet_skin_used_up(double max_particle_displacement) const noexcept;
  /// Sets whether the next step rebuilds: a decomposed run replaces each
  /// part's own decision by the whole body's.
  void set_lists_stale(bool stale) noexcept { stale_ = stale; }
  /// m, the cell size of the last rebuild's grid: the slots are in the order
  /// of the cells floor(x_ref / size) (x_ref: reference_positions()), then ids.
  [[nodiscard]] double cell_size() const noexcept { return cell_size_; }
  /// Wall `w` for its result fields alone (forces, moment: a decomposed run
  /// puts the whole body's there); geometry and motion must not change.
  [[nodiscard]] Wall& wall_results_for_edit(std::size_t w) { return walls_.at(w); }

  /// Makes the space periodic on cell.periodic's axes (and deformable).
  /// Throws UserError if a periodic edge is shorter than 2 (2 r_max + skin).
  void set_periodic_cell(const PeriodicCell& cell);
  /// 1/s, the cell's edge strain rates for the following steps (needs a cell).
  void set_cell_strain_rate(const Vec3& rate);

  // State ---------------------------------------------------------------------
  [[nodiscard]] const ParticleStore& particles() const noexcept { return particles_; }
  [[nodiscard]] const std::vector<Wall>& walls() const noexcept { return walls_; }
  [[nodiscard]] const PairContacts& pair_contacts() const noexcept { return pairs_; }
  /// N, the sum over particles of the local-damping force of the last step
  /// (F_d - F, integrator.hpp; zero without damping). Local damping is a
  /// force on each particle that no wall or continuum carries: the momentum
  /// balance of the particles is  dP/dt = weight + wall and coupling
  /// reactions + this.
  [[nodiscard]] Vec3 damping_force_total() const;
  /// N, per slot: the local-damping force of the last step, F_d - F (empty undamped).
  [[nodiscard]] std::span<const Vec3> damping_forces() const noexcept { return damping_force_; }
  /// Changes alpha of local damping from the next step on (a loading stage's
  /// own damping); UserError outside [0, 1).
  void set_local_damping(double alpha);
  /// N s, the particles' momentum sum of m v (translational velocities of the last step).
  [[nodiscard]] Vec3 momentum() const;
  [[nodiscard]] const WallContacts& wall_contacts(std::size_t wall) const { return wall_contacts_.at(wall); }
  /// Logic error after a step that recorded only the gathered outputs.
  [[nodiscard]] const ContactOutputs& contact_outputs() const;
  /// False only after a step that recorded the gathered outputs alone: in the
  /// middle of a run, or when such a step failed (SolverError).
  [[nodiscard]] bool contact_outputs_complete() const noexcept { return outputs_complete_; }
  /// The outputs whatever the last step recorded: its wall contacts' entries
  /// are always written (ContactRecord), the pairs' may be stale.
  [[nodiscard]] const ContactOutputs& outputs_with_wall_contacts() const noexcept { return outputs_; }
  /// Where wall `wall`'s contacts start in contact_outputs().
  [[nodiscard]] std::size_t wall_output_offset(std::size_t wall) const { return wall_offsets_.at(wall); }
  [[nodiscard]] std::int64_t step_count() const noexcept { return step_; }
  [[nodiscard]] std::size_t rebuild_count() const noexcept { return rebuilds_; }
  [[nodiscard]] double skin() const noexcept { return skin_; }
  [[nodiscard]] int threads() const noexcept { return threads_; }
  [[nodiscard]] const SimulationSettings& settings() const noexcept { return settings_; }
  [[nodiscard]] const ParticleMaterials& materials() const noexcept { return materials_; }
  [[nodiscard]] const std::optional<PeriodicCell>& periodic_cell() const noexcept { return cell_; }
  [[nodiscard]] bool bonds_installed() const noexcept { return bonds_installed_; }
  /// Bonds by state over the particle pairs (all zero for an unbonded law).
  [[nodiscard]] BondCounts bond_counts() const noexcept;

  // Checkpoint (simulation_checkpoint.cpp) ------------------------------------
  /// Every member that changes while the simulation runs, as raw bytes: the
  /// contact lists in their order, the Verlet references, the step counters.
  void save_state(StateWriter& out) const;
  /// Replaces the running state by save_state()'s of a simulation built from
  /// the same settings and walls; the next step is the one the saved
  /// simulation would have taken. Throws StateFormatError when they differ.
  void load_state(StateReader& in);

 private:
  /// save_state and load_state: one field list for both directions
  /// (Self = const Simulation writes, Simulation reads).
  template <class Archive, class Self>
  static void transfer_state(Archive& a, Self& s);
  /// load_state's checks of the pair lists it read against this model.
  void check_pair_state(const StateReader& in) const;

  void rebuild();
  /// The rebuild's radii: r_max (with the body's), skin and search distance.
  struct SearchRadii {
    double r_max, skin, search;
    bool install, join;
  };
  [[nodiscard]] SearchRadii search_radii() const;
  /// Appends the pairs of `archive` with a bond (ever) that the search did not find.
  void append_persistent_pairs(const HistoryArchive& archive);
  /// The same for a rebuild by slot: the bonded pairs of `before` that no new
  /// pair matched, appended in id order with their index in `match`
  /// (`old_to_new`: the inverse of the rebuild's re-sort, as match_previous_pairs takes it).
  void append_unmatched_bonds(const PairContacts& before, std::span<const std::uint32_t> old_to_new, std::vector<std::uint32_t>& match);
  /// Bonds every pair with a surface gap <= its law's bond gap (first
  /// rebuild); with `across_materials_only`, only unbonded pairs of particles
  /// of different materials whose history is empty.
  void install_bonds(bool across_materials_only);
  /// After a search beyond the skin (to install bonds or join the zones'
  /// seams): drops the candidates a search to the skin would not have found
  /// and that hold no bond (ever), as the next rebuild would. They carry
  /// nothing, yet each step read their rows until then (the paper model:
  /// 4.59 instead of 4.07 candidates per particle for its first ~270 steps).
  void drop_pairs_beyond_skin();
  /// PairContacts::law_index for the new lists (more than one material).
  void assign_pair_laws();
  /// The particle law's pair constants for the new lists (contact_forces.cpp).
  void compute_pair_constants();
  /// Step 2 of the cycle (contact_forces.cpp). Returns true on an excessive overlap.
  bool compute_contact_forces(double dt, ContactRecord record);
  /// After compute_contact_forces returned true: the contact with the largest
  /// overlap relative to the guarded radius, its particles and bond state
  /// (contacts/overlap_report.cpp), for the error message.
  [[nodiscard]] std::string describe_largest_overlap() const;
  /// The seam balance of bond_across_materials_now (contacts/seam_balance_step.cpp).
  void balance_seams(double dt);
  void move_walls(double dt);
  /// m, the largest edge a pair search needs: 2 r_max + search distance.
  void check_cell_width(double reach) const;

  SimulationSettings settings_;
  ParticleMaterials materials_;  ///< settings_.particle_law, then material_laws
  int threads_ = 1;
  double skin_ = 0.0;
  double r_max_ = 0.0;  ///< m, largest radius at the last rebuild
  double body_r_max_ = 0.0;  ///< m, set_body_extent (0: this body's own)
  double cell_size_ = 0.0;   ///< m, the last rebuild's grid cell size
  std::optional<BodyBounds> body_bounds_;  ///< set_body_extent
  ParticleStore particles_;
  std::unordered_set<std::int64_t> ids_;
  std::vector<std::int64_t> ids_at_rebuild_;  ///< particle ids by slot after the last rebuild: pairs_ may carry history by slot
  std::vector<Wall> walls_;
  mutable std::optional<double> critical_step_;  ///< critical_timestep() of the present particles and walls

  PairContacts pairs_;
  std::vector<WallContacts> wall_contacts_;
  std::vector<std::size_t> wall_offsets_;
  ContactOutputs outputs_;
  bool outputs_complete_ = true;  ///< false after a step with ContactRecord::gathered_only
  Incidence incidence_;
  std::vector<Vec3> reference_positions_;                 ///< particle positions at the last rebuild
  std::vector<Vec3> damping_force_;                       ///< N, per slot: local-damping force of the last step (empty undamped)
  std::vector<std::vector<Vec3>> reference_vertices_;     ///< wall vertices at the last rebuild
  double max_wall_displacement_ = 0.0;                    ///< m, since the last rebuild

  std::int64_t step_ = 0;
  std::size_t rebuilds_ = 0;
  bool stale_ = true;
  bool bonds_installed_ = false;
  bool install_requested_ = false;
  bool join_materials_requested_ = false;
  double last_search_ = 0.0;              ///< m, the search radius of the last rebuild
  std::optional<double> repeat_search_;   ///< repeat_last_search(), taken by the next rebuild
  SeamBalanceReport seam_report_;

  std::optional<HistoryArchive> seeded_pairs_;  ///< seed_pair_history(), consumed by the next rebuild
  std::optional<std::vector<HistoryArchive>> seeded_walls_;  ///< replace_body()'s wall rows, consumed by the next rebuild

  std::optional<PeriodicCell> cell_;
  double affine_approach_ = 0.0;  ///< m, bound on how far the cell's deformation moved two partners together since the last rebuild
};

}  // namespace dfc::dem
