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
  std::vector<double> history;
  std::size_t constants_stride;
  std::vector<double> constants;
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

void write_particles(StateWriter& out, const ParticleStore& p) {
  out.tag("particles");
  out.vector(p.id);
  out.vector(p.position);
  out.vector(p.velocity);
  out.vector(p.angular_velocity);
  out.vector(p.force);
  out.vector(p.moment);
  out.vector(p.radius);
  out.vector(p.mass);
  out.vector(p.inertia);
  out.vector(p.material);
}

void read_particles(StateReader& in, ParticleStore& p) {
  in.tag("particles");
  in.vector(p.id);
  in.vector(p.position);
  in.vector(p.velocity);
  in.vector(p.angular_velocity);
  in.vector(p.force);
  in.vector(p.moment);
  in.vector(p.radius);
  in.vector(p.mass);
  in.vector(p.inertia);
  in.vector(p.material);
  const std::size_t n = p.id.size();
  for (const std::size_t size : {p.position.size(), p.velocity.size(), p.angular_velocity.size(), p.force.size(), p.moment.size(),
                                 p.radius.size(), p.mass.size(), p.inertia.size(), p.material.size()})
    if (size != n) in.fail("particle arrays of " + std::to_string(n) + " entries each");
}

/// The running state of a wall; its name, motion kind, law and facets are the model's and are checked.
void write_wall(StateWriter& out, const Wall& w) {
  out.tag("wall");
  out.string(w.name);
  out.value(w.motion);
  out.vector(w.facets);
  out.value(w.prescribed_velocity);
  out.value(w.start_step);
  out.vector(w.vertices);
  out.vector(w.vertex_velocity);
  out.vector(w.vertex_force);
  out.value(w.force);
  out.value(w.moment);
  out.value(w.force_on_particles);
  out.vector(w.facet_force);
}

void read_wall(StateReader& in, Wall& w) {
  in.tag("wall");
  const std::string name = in.string();
  const auto motion = in.value<WallMotion>();
  std::vector<Facet> facets;
  in.vector(facets);
  if (name != w.name || motion != w.motion || facets != w.facets)
    in.fail("wall \"" + w.name + "\" with its " + std::to_string(w.facets.size()) + " facets (the checkpoint has wall \"" + name + "\" with " +
            std::to_string(facets.size()) + "): the model's walls differ from the saved run's");
  in.value(w.prescribed_velocity);
  in.value(w.start_step);
  const std::size_t vertices = w.vertices.size();
  in.vector(w.vertices);
  in.vector(w.vertex_velocity);
  in.vector(w.vertex_force);
  if (w.vertices.size() != vertices || w.vertex_velocity.size() != vertices || w.vertex_force.size() != vertices)
    in.fail("wall \"" + w.name + "\" with " + std::to_string(vertices) + " vertices");
  in.value(w.force);
  in.value(w.moment);
  in.value(w.force_on_particles);
  const std::size_t facet_forces = w.facet_force.size();
  in.vector(w.facet_force);
  if (w.facet_force.size() != facet_forces) in.fail("wall \"" + w.name + "\" with " + std::to_string(facet_forces) + " facet forces");
}

void write_wall_contacts(StateWriter& out, const WallContacts& c) {
  out.tag("wall contacts");
  out.vector(c.particle);
  out.vector(c.facet);
  out.vector(c.group_start);
  out.value(c.stride);
  out.vector(c.history);
  out.vector(c.weights);
  out.vector(c.distance);
  out.vector(c.feature);
  out.vector(c.selected);
}

void read_wall_contacts(StateReader& in, WallContacts& c) {
  in.tag("wall contacts");
  in.vector(c.particle);
  in.vector(c.facet);
  in.vector(c.group_start);
  in.value(c.stride);
  in.vector(c.history);
  in.vector(c.weights);
  in.vector(c.distance);
  in.vector(c.feature);
  in.vector(c.selected);
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
  ParticleStore particles_;
  std::unordered_set<std::int64_t> ids_;
  std::vector<Wall> walls_;
  PairContacts pairs_;
  std::vector<WallContacts> wall_contacts_;
  std::vector<std::size_t> wall_offsets_;
  ContactOutputs outputs_;
  bool outputs_complete_;
  Incidence incidence_;
  std::vector<Vec3> reference_positions_;
  std::vector<std::vector<Vec3>> reference_vertices_;
  double max_wall_displacement_;
  std::int64_t step_;
  std::size_t rebuilds_;
  bool stale_, bonds_installed_, install_requested_, join_materials_requested_;
  SeamBalanceReport seam_report_;
  std::optional<HistoryArchive> seeded_pairs_;
  std::optional<PeriodicCell> cell_;
  double affine_approach_;
};
static_assert(sizeof(Simulation) == sizeof(SimulationLayout), "a Simulation member is missing from Simulation::save_state");

void Simulation::save_state(StateWriter& out) const {
  out.tag("simulation");
  out.value(skin_);
  out.value(r_max_);
  write_particles(out, particles_);
  out.value(walls_.size());
  for (const Wall& w : walls_) write_wall(out, w);
  out.tag("pairs");
  out.vector(pairs_.first);
  out.vector(pairs_.second);
  out.value(pairs_.stride);
  out.vector(pairs_.history);
  out.value(pairs_.constants_stride);
  out.vector(pairs_.constants);
  out.vector(pairs_.law_index);
  for (const WallContacts& c : wall_contacts_) write_wall_contacts(out, c);
  out.vector(wall_offsets_);
  out.tag("outputs");
  out.vector(outputs_.force);
  out.vector(outputs_.point);
  out.vector(outputs_.couple);
  out.vector(outputs_.shift);
  out.value(outputs_complete_);
  out.tag("incidence");
  out.vector(incidence_.start);
  out.vector(incidence_.entry);
  out.vector(incidence_.chunk_start);
  out.vector(incidence_.gather_from);
  out.vector(incidence_.direct);
  out.tag("verlet");
  out.vector(reference_positions_);
  out.value(reference_vertices_.size());
  for (const auto& vertices : reference_vertices_) out.vector(vertices);
  out.value(max_wall_displacement_);
  out.value(step_);
  out.value(rebuilds_);
  out.value(stale_);
  out.value(bonds_installed_);
  out.value(install_requested_);
  out.value(join_materials_requested_);
  out.value(seam_report_);
  write_archive(out, seeded_pairs_);
  out.optional(cell_);
  out.value(affine_approach_);
}

void Simulation::load_state(StateReader& in) {
  in.tag("simulation");
  in.value(skin_);
  in.value(r_max_);
  read_particles(in, particles_);
  ids_ = std::unordered_set<std::int64_t>(particles_.id.begin(), particles_.id.end());
  if (ids_.size() != particles_.size()) in.fail("unique particle ids");
  const auto walls = in.value<std::size_t>();
  if (walls != walls_.size())
    in.fail(std::to_string(walls_.size()) + " walls as this model has (the checkpoint has " + std::to_string(walls) +
            "; a coupling wall comes with set_interface, before restore)");
  for (Wall& w : walls_) read_wall(in, w);
  in.tag("pairs");
  in.vector(pairs_.first);
  in.vector(pairs_.second);
  in.value(pairs_.stride);
  in.vector(pairs_.history);
  in.value(pairs_.constants_stride);
  in.vector(pairs_.constants);
  in.vector(pairs_.law_index);
  if (!pairs_.law_index.empty() && pairs_.law_index.size() != pairs_.first.size()) in.fail("a pair law index per pair contact");
  for (const std::uint16_t index : pairs_.law_index)
    if (index >= materials_.count() * materials_.count()) in.fail("pair law indices of this model's " + std::to_string(materials_.count()) + " materials");
  for (const std::uint16_t m : particles_.material)
    if (m >= materials_.count()) in.fail("particle materials of this model's " + std::to_string(materials_.count()) + " materials");
  if (pairs_.stride != settings_.particle_law.history_size()) in.fail("pair history rows of the particle law's width");
  for (WallContacts& c : wall_contacts_) read_wall_contacts(in, c);
  in.vector(wall_offsets_);
  in.tag("outputs");
  in.vector(outputs_.force);
  in.vector(outputs_.point);
  in.vector(outputs_.couple);
  in.vector(outputs_.shift);
  in.value(outputs_complete_);
  in.tag("incidence");
  in.vector(incidence_.start);
  in.vector(incidence_.entry);
  in.vector(incidence_.chunk_start);
  in.vector(incidence_.gather_from);
  in.vector(incidence_.direct);
  in.tag("verlet");
  in.vector(reference_positions_);
  const auto references = in.value<std::size_t>();
  if (references != 0 && references != walls_.size()) in.fail("the Verlet references of every wall");
  reference_vertices_.resize(references);  // none before the first rebuild
  for (auto& vertices : reference_vertices_) in.vector(vertices);
  in.value(max_wall_displacement_);
  in.value(step_);
  in.value(rebuilds_);
  in.value(stale_);
  in.value(bonds_installed_);
  in.value(install_requested_);
  in.value(join_materials_requested_);
  in.value(seam_report_);
  read_archive(in, seeded_pairs_);
  in.optional(cell_);
  in.value(affine_approach_);
}

}  // namespace dfc::dem
