// Simulation::save_state / load_state: the DEM's running state as raw bytes
// (protocol/SPEC.md §4.7, docs/checkpoints.md).
//
// Why raw: a restored run must take the very steps the uninterrupted one
// takes. Re-deriving anything (a neighbour search, the pair orientation, the
// incidence) could give another contact order, hence other summation orders
// and other bits. So every member that changes while the simulation runs is
// stored as it is: particles in their slot order, the pair and facet lists
// with every history column and their per-pair constants, the last contact
// outputs, the incidence, the Verlet references (a rebuild then falls on the
// same step), the wall kinematics and loads, the periodic cell, the counters.
// What the settings and walls define (the laws, facet topology, thread
// count) comes from configure and is checked, not stored.
//
// The layout asserts below fail to compile when a member is added to one of
// the stored types: add it to save_state/load_state, then to the assert.
#include <string>
#include <type_traits>

#include "dfc/common/state_archive.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

namespace {

struct ParticleStoreLayout {
  std::vector<std::int64_t> id;
  std::vector<Vec3> position, velocity, angular_velocity, force, moment;
  std::vector<double> radius, mass, inertia;
  std::vector<std::uint16_t> material;
};
static_assert(sizeof(ParticleStore) == sizeof(ParticleStoreLayout), "a ParticleStore field is missing from Simulation::save_state");

struct WallLayout {
  std::string name;
  WallMotion motion;
  Vec3 prescribed_velocity;
  std::int64_t start_step;
  ContactLawSetting law;
  std::vector<Vec3> vertices, vertex_velocity;
  std::vector<Facet> facets;
  std::vector<Vec3> vertex_force;
  Vec3 force, moment, force_on_particles;
  std::vector<Vec3> facet_force;
};
static_assert(sizeof(Wall) == sizeof(WallLayout), "a Wall field is missing from Simulation::save_state");

struct PairContactsLayout {
  std::vector<std::uint32_t> first, second;
  std::size_t stride;
  UninitialisedDoubles history;
  std::size_t cold_stride;
  UninitialisedDoubles cold_history;
  std::size_t constants_stride;
  UninitialisedDoubles constants;
  std::vector<std::uint16_t> law_index;
};
static_assert(sizeof(PairContacts) == sizeof(PairContactsLayout), "a PairContacts field is missing from Simulation::save_state");

struct WallContactsLayout {
  std::vector<std::uint32_t> particle, facet, group_start;
  std::size_t stride;
  std::vector<double> history;
  std::vector<std::array<double, 3>> weights;
  std::vector<double> distance;
  std::vector<std::uint8_t> feature, selected;
};
static_assert(sizeof(WallContacts) == sizeof(WallContactsLayout), "a WallContacts field is missing from Simulation::save_state");

struct ContactOutputsLayout {
  std::vector<Vec3> force, point, couple, shift;
};
static_assert(sizeof(ContactOutputs) == sizeof(ContactOutputsLayout), "a ContactOutputs field is missing from Simulation::save_state");

struct IncidenceLayout {
  std::vector<std::uint32_t> start, entry;
  std::vector<std::size_t> chunk_start;
  std::vector<std::uint32_t> gather_from;
  std::vector<std::uint8_t> direct;
};
static_assert(sizeof(Incidence) == sizeof(IncidenceLayout), "an Incidence field is missing from Simulation::save_state");

static_assert(std::is_trivially_copyable_v<PeriodicCell>, "PeriodicCell is stored as its bytes");

/// True when `Archive` reads (load_state), false when it writes (save_state).
template <class Archive>
inline constexpr bool reading = std::is_same_v<Archive, StateReader>;

// One field list per stored type, serving both directions: the writer gets
// const members, the reader mutable ones, in the same order by construction.
// `Store` is the type, const for the writer.

template <class Archive, class Store>
void transfer_particles(Archive& a, Store& p) {
  a.tag("particles");
  a.vector(p.id);
  a.vector(p.position);
  a.vector(p.velocity);
  a.vector(p.angular_velocity);
  a.vector(p.force);
  a.vector(p.moment);
  a.vector(p.radius);
  a.vector(p.mass);
  a.vector(p.inertia);
  a.vector(p.material);
}

void check_particles(const StateReader& in, const ParticleStore& p) {
  const std::size_t n = p.id.size();
  for (const std::size_t size : {p.position.size(), p.velocity.size(), p.angular_velocity.size(), p.force.size(), p.moment.size(),
                                 p.radius.size(), p.mass.size(), p.inertia.size(), p.material.size()})
    if (size != n) in.fail("particle arrays of " + std::to_string(n) + " entries each");
}

/// A wall's name, motion kind and facets are the model's: written, and on
/// reading compared with the configured wall's.
void transfer_wall_identity(StateWriter& out, const Wall& w) {
  out.string(w.name);
  out.value(w.motion);
  out.vector(w.facets);
}

void transfer_wall_identity(StateReader& in, const Wall& w) {
  const std::string name = in.string();
  const auto motion = in.value<WallMotion>();
  std::vector<Facet> facets;
  in.vector(facets);
  if (name != w.name || motion != w.motion || facets != w.facets)
    in.fail("wall \"" + w.name + "\" with its " + std::to_string(w.facets.size()) + " facets (the checkpoint has wall \"" + name + "\" with " +
            std::to_string(facets.size()) + "): the model's walls differ from the saved run's");
}

/// The running state of a wall.
template <class Archive, class Store>
void transfer_wall(Archive& a, Store& w) {
  a.tag("wall");
  transfer_wall_identity(a, w);
  const std::size_t vertices = w.vertices.size(), facet_forces = w.facet_force.size();
  a.value(w.prescribed_velocity);
  a.value(w.start_step);
  a.vector(w.vertices);
  a.vector(w.vertex_velocity);
  a.vector(w.vertex_force);
  a.value(w.force);
  a.value(w.moment);
  a.value(w.force_on_particles);
  a.vector(w.facet_force);
  if constexpr (reading<Archive>) {
    if (w.vertices.size() != vertices || w.vertex_velocity.size() != vertices || w.vertex_force.size() != vertices)
      a.fail("wall \"" + w.name + "\" with " + std::to_string(vertices) + " vertices");
    if (w.facet_force.size() != facet_forces) a.fail("wall \"" + w.name + "\" with " + std::to_string(facet_forces) + " facet forces");
  }
}

template <class Archive, class Store>
void transfer_wall_contacts(Archive& a, Store& c) {
  a.tag("wall contacts");
  a.vector(c.particle);
  a.vector(c.facet);
  a.vector(c.group_start);
  a.value(c.stride);
  a.vector(c.history);
  a.vector(c.weights);
  a.vector(c.distance);
  a.vector(c.feature);
  a.vector(c.selected);
}

void write_archive(StateWriter& out, const std::optional<HistoryArchive>& archive) {
  out.value(std::uint8_t(archive.has_value()));
  if (!archive) return;
  out.value(archive->stride());
  out.value(archive->size());
  for (std::size_t k = 0; k < archive->size(); ++k) {
    out.value(archive->key(k));
    for (std::size_t c = 0; c < archive->stride(); ++c) out.value(archive->row(k)[c]);
  }
}

void read_archive(StateReader& in, std::optional<HistoryArchive>& archive) {
  archive.reset();
  if (in.value<std::uint8_t>() == 0) return;
  const auto stride = in.value<std::size_t>();
  const auto rows = in.value<std::size_t>();
  if (rows > in.remaining() / (sizeof(HistoryArchive::Key) + stride * sizeof(double))) in.fail("a pair history of " + std::to_string(rows) + " rows");
  HistoryArchive result(stride);
  std::vector<double> row(stride);
  for (std::size_t k = 0; k < rows; ++k) {
    const auto key = in.value<HistoryArchive::Key>();
    for (double& v : row) in.value(v);
    result.add(key, row.data());  // in insertion order, then sealed: the same archive
  }
  result.seal();
  archive = std::move(result);
}

}  // namespace

// Mirrors Simulation's members in declaration order (simulation.hpp).
struct SimulationLayout {
  SimulationSettings settings_;
  ParticleMaterials materials_;
  int threads_;
  double skin_, r_max_;
  double body_r_max_;                     // not saved: a decomposed run sets it before each rebuild
  double cell_size_;                      // not saved: read by a decomposed run, which rebuilds at once after a decomposition
  std::optional<BodyBounds> body_bounds_;  // likewise
  ParticleStore particles_;
  std::unordered_set<std::int64_t> ids_;
  std::vector<std::int64_t> ids_at_rebuild_;  // not saved: the first rebuild after a restore carries history by id
  std::vector<Wall> walls_;
  std::optional<double> critical_step_;  // a cache of critical_timestep(): recomputed, not saved
  PairContacts pairs_;
  std::vector<WallContacts> wall_contacts_;
  std::vector<std::size_t> wall_offsets_;
  ContactOutputs outputs_;
  bool outputs_complete_;
  Incidence incidence_;
  std::vector<Vec3> reference_positions_;
  std::vector<Vec3> damping_force_;
  std::vector<std::vector<Vec3>> reference_vertices_;
  double max_wall_displacement_;
  std::int64_t step_;
  std::size_t rebuilds_;
  bool stale_, bonds_installed_, install_requested_, join_materials_requested_;
  double last_search_;                   // not saved: read only by repeat_last_search, which a decomposed body's first step calls
  std::optional<double> repeat_search_;  // not saved: set and taken within that step
  SeamBalanceReport seam_report_;
  std::optional<HistoryArchive> seeded_pairs_;
  std::optional<std::vector<HistoryArchive>> seeded_walls_;  // not saved: replace_body's, taken by the rebuild that follows it at once
  std::optional<PeriodicCell> cell_;
  double affine_approach_;
};
static_assert(sizeof(Simulation) == sizeof(SimulationLayout), "a Simulation member is missing from Simulation::save_state");

template <class Archive, class Self>
void Simulation::transfer_state(Archive& a, Self& s) {
  a.tag("simulation");
  a.value(s.skin_);
  a.value(s.r_max_);
  transfer_particles(a, s.particles_);
  std::size_t walls = s.walls_.size();
  a.value(walls);
  if constexpr (reading<Archive>) {
    s.ids_ = std::unordered_set<std::int64_t>(s.particles_.id.begin(), s.particles_.id.end());
    if (s.ids_.size() != s.particles_.size()) a.fail("unique particle ids");
    check_particles(a, s.particles_);
    if (walls != s.walls_.size())
      a.fail(std::to_string(s.walls_.size()) + " walls as this model has (the checkpoint has " + std::to_string(walls) +
             "; a coupling wall comes with set_interface, before restore)");
  }
  for (auto& w : s.walls_) transfer_wall(a, w);
  a.tag("pairs");
  a.vector(s.pairs_.first);
  a.vector(s.pairs_.second);
  a.value(s.pairs_.stride);
  a.vector(s.pairs_.history);
  a.value(s.pairs_.cold_stride);
  a.vector(s.pairs_.cold_history);
  a.value(s.pairs_.constants_stride);
  a.vector(s.pairs_.constants);
  a.vector(s.pairs_.law_index);
  if constexpr (reading<Archive>) s.check_pair_state(a);
  for (auto& c : s.wall_contacts_) transfer_wall_contacts(a, c);
  a.vector(s.wall_offsets_);
  a.tag("outputs");
  a.vector(s.outputs_.force);
  a.vector(s.outputs_.point);
  a.vector(s.outputs_.couple);
  a.vector(s.outputs_.shift);
  a.value(s.outputs_complete_);
  a.tag("incidence");
  a.vector(s.incidence_.start);
  a.vector(s.incidence_.entry);
  a.vector(s.incidence_.chunk_start);
  a.vector(s.incidence_.gather_from);
  a.vector(s.incidence_.direct);
  a.tag("verlet");
  a.vector(s.reference_positions_);
  a.vector(s.damping_force_);
  std::size_t references = s.reference_vertices_.size();
  a.value(references);
  if constexpr (reading<Archive>) {
    if (references != 0 && references != s.walls_.size()) a.fail("the Verlet references of every wall");
    s.reference_vertices_.resize(references);  // none before the first rebuild
  }
  for (auto& vertices : s.reference_vertices_) a.vector(vertices);
  a.value(s.max_wall_displacement_);
  a.value(s.step_);
  a.value(s.rebuilds_);
  a.value(s.stale_);
  a.value(s.bonds_installed_);
  a.value(s.install_requested_);
  a.value(s.join_materials_requested_);
  a.value(s.seam_report_);
  if constexpr (reading<Archive>) read_archive(a, s.seeded_pairs_);
  else write_archive(a, s.seeded_pairs_);
  a.optional(s.cell_);
  a.value(s.affine_approach_);
}

void Simulation::check_pair_state(const StateReader& in) const {
  if (!pairs_.law_index.empty() && pairs_.law_index.size() != pairs_.first.size()) in.fail("a pair law index per pair contact");
  for (const std::uint16_t index : pairs_.law_index)
    if (index >= materials_.count() * materials_.count()) in.fail("pair law indices of this model's " + std::to_string(materials_.count()) + " materials");
  for (const std::uint16_t m : particles_.material)
    if (m >= materials_.count()) in.fail("particle materials of this model's " + std::to_string(materials_.count()) + " materials");
  if (pairs_.whole_stride() != settings_.particle_law.history_size() || pairs_.cold_stride != settings_.particle_law.cold_history_size() ||
      pairs_.history.size() != pairs_.size() * pairs_.stride || pairs_.cold_history.size() != pairs_.size() * pairs_.cold_stride)
    in.fail("pair history rows of the particle law's width");
}

void Simulation::save_state(StateWriter& out) const { transfer_state(out, *this); }

void Simulation::load_state(StateReader& in) {
  transfer_state(in, *this);
  ids_at_rebuild_.clear();  // the first rebuild carries the restored history by id (HistoryArchive), as any other
  // The pair constants follow from the radii, masses and laws alone: computed
  // again, they are the same bits, and a checkpoint written before a law had
  // constants (its stride 0) resumes with them.
  compute_pair_constants();
}

}  // namespace dfc::dem
