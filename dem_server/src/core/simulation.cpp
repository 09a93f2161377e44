#include "dfc/dem/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include <omp.h>

#include "dfc/common/errors.hpp"
#include "dfc/common/work_progress.hpp"
#include "dfc/dem/exact_sum.hpp"
#include "dfc/dem/fixed_order_sum.hpp"
#include "dfc/dem/huge_pages.hpp"
#include "dfc/dem/integrator.hpp"
#include "dfc/dem/neighbour_search.hpp"
#include "dfc/dem/parallel.hpp"
#include "dfc/dem/timestep.hpp"
#include "dfc/dem/wall_forces.hpp"

namespace dfc::dem {

namespace {
/// Relative tolerance of the bonding test (install_bonds): far above the
/// round-off of a centre distance, far below any physical bond gap.
constexpr double bonding_round_off = 1e-9;
}  // namespace

namespace {
std::vector<ContactLawSetting> all_materials(const SimulationSettings& settings) {
  if (settings.particle_law.info == nullptr) throw UserError("the simulation needs a particle contact law");
  std::vector<ContactLawSetting> out{settings.particle_law};
  out.insert(out.end(), settings.material_laws.begin(), settings.material_laws.end());
  return out;
}
}  // namespace

Simulation::Simulation(SimulationSettings settings) : settings_(std::move(settings)), materials_(all_materials(settings_)) {
  if (!(settings_.local_damping >= 0.0 && settings_.local_damping < 1.0)) throw UserError("local damping must be in [0, 1)");
  threads_ = settings_.threads > 0 ? settings_.threads : omp_get_max_threads();
  pairs_.set_strides(settings_.particle_law.history_size(), settings_.particle_law.cold_history_size());
}

void Simulation::add_sphere(std::int64_t id, Vec3 centre, double radius, double density, MaterialId material) {
  if (material >= materials_.count())
    throw UserError("particle " + std::to_string(id) + " has material " + std::to_string(material) + " but the simulation has " +
                    std::to_string(materials_.count()) + " materials");
  if (!ids_.insert(id).second) throw UserError("particle id " + std::to_string(id) + " is used twice; ids must be unique");
  particles_.add_sphere(id, centre, radius, density, material);
  critical_step_.reset();
  stale_ = true;
}

ParticleStore& Simulation::particles_for_edit() {
  critical_step_.reset();  // the caller may change radii or masses
  stale_ = true;
  return particles_;
}

std::size_t Simulation::add_wall(Wall wall) {
  walls_.push_back(std::move(wall));
  wall_contacts_.emplace_back();
  critical_step_.reset();
  stale_ = true;
  return walls_.size() - 1;
}

void Simulation::replace_wall(std::size_t index, Wall wall) {
  walls_.at(index) = std::move(wall);
  wall_contacts_.at(index) = WallContacts{};  // facet indices changed meaning: no history to carry
  critical_step_.reset();
  stale_ = true;
}

void Simulation::set_vertex_velocities(std::size_t wall, std::span<const Vec3> velocity) {
  Wall& w = walls_.at(wall);
  if (velocity.size() != w.vertex_count())
    throw UserError("wall \"" + w.name + "\" has " + std::to_string(w.vertex_count()) + " vertices but " + std::to_string(velocity.size()) +
                    " velocities were given");
  std::copy(velocity.begin(), velocity.end(), w.vertex_velocity.begin());
}

void Simulation::set_wall_velocity(std::size_t wall, const Vec3& velocity) {
  Wall& w = walls_.at(wall);
  if (w.motion != WallMotion::prescribed) throw UserError("wall \"" + w.name + "\" follows the continuum; its velocity cannot be prescribed");
  w.prescribed_velocity = velocity;
}

double Simulation::critical_timestep() const {
  if (!critical_step_) {
    const auto bound = [this](double radius) {
      StiffnessBound k = materials_.stiffness_bound(radius);
      for (const auto& w : walls_) k = stiffest(k, w.law.stiffness_bound(radius));
      return k;
    };
    critical_step_ = dfc::dem::critical_timestep(particles_, bound, settings_.step_bound);
  }
  return *critical_step_;
}

void Simulation::install_bonds_now() noexcept {
  if (bonds_installed_) return;
  install_requested_ = true;
  stale_ = true;
}

void Simulation::bond_across_materials_now() noexcept {
  join_materials_requested_ = true;
  stale_ = true;
}

void Simulation::seed_pair_history(HistoryArchive archive, bool bonds_installed) {
  if (archive.stride() != settings_.particle_law.history_size())
    throw UserError("seeded pair history has " + std::to_string(archive.stride()) + " columns but the particle law keeps " +
                    std::to_string(settings_.particle_law.history_size()));
  seeded_pairs_ = std::move(archive);
  bonds_installed_ = bonds_installed_ || bonds_installed;
  stale_ = true;
}

std::size_t Simulation::remove_particles_before_start(const std::function<bool(std::size_t slot)>& remove) {
  if (step_ != 0) throw UserError("particles can only be removed before the first step");
  std::vector<std::uint32_t> kept;
  std::unordered_set<std::int64_t> removed;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (remove(i)) removed.insert(particles_.id[i]);
    else kept.push_back(std::uint32_t(i));
  }
  if (removed.empty()) return 0;
  if (!seeded_pairs_) seeded_pairs_ = archive_history(pairs_, particles_);
  seeded_pairs_->retain([&](const HistoryArchive::Key& key) { return !removed.contains(key[0]) && !removed.contains(key[1]); });
  particles_.retain(kept);
  critical_step_.reset();
  for (const std::int64_t id : removed) ids_.erase(id);
  pairs_ = PairContacts{};
  for (auto& w : wall_contacts_) w = WallContacts{};
  stale_ = true;
  return removed.size();
}

void Simulation::set_periodic_cell(const PeriodicCell& cell) {
  const Vec3 l = cell.length();
  if (!(l.x > 0.0 && l.y > 0.0 && l.z > 0.0)) throw UserError("the periodic cell needs hi > lo on every axis");
  cell_ = cell;
  stale_ = true;
  const double r_max = largest_radius(particles_);
  check_cell_width(2.0 * r_max + (settings_.skin > 0.0 ? settings_.skin : 0.2 * r_max));
}

void Simulation::set_cell_strain_rate(const Vec3& rate) {
  if (!cell_) throw UserError("a cell strain rate needs a periodic cell");
  cell_->strain_rate = rate;
}

void Simulation::check_cell_width(double reach) const {
  if (!cell_) return;
  const Vec3 l = cell_->length();
  const double edge[3] = {l.x, l.y, l.z};
  for (std::size_t a = 0; a < 3; ++a) {
    if (!cell_->periodic[a] || edge[a] >= 2.0 * reach) continue;
    std::ostringstream msg;
    msg << "the periodic cell is " << edge[a] << " m long along " << "xyz"[a] << " but must be at least 2 (2 r_max + skin) = " << 2.0 * reach
        << " m so that the minimum image of every contact is unique; use a larger cell or smaller particles";
    throw UserError(msg.str());
  }
}

Simulation::SearchRadii Simulation::search_radii() const {
  SearchRadii r{};
  r.r_max = std::max(largest_radius(particles_), body_r_max_);
  r.skin = settings_.skin > 0.0 ? settings_.skin : 0.2 * r.r_max;
  // Installing bonds needs every pair within the bonding gap, which may exceed the skin.
  r.install = settings_.particle_law.bonded() && !bonds_installed_ && (settings_.install_bonds_at_start || install_requested_);
  r.join = settings_.particle_law.bonded() && join_materials_requested_;
  r.search = r.install || r.join ? std::max(r.skin, 1.001 * materials_.largest_bond_gap()) : r.skin;
  if (repeat_search_) r.search = std::max(r.search, *repeat_search_);
  return r;
}

double Simulation::next_search_reach() const {
  const SearchRadii r = search_radii();
  return 2.0 * r.r_max + r.search;
}

void Simulation::replace_body(ParticleStore particles, HistoryArchive pairs, std::vector<HistoryArchive> wall_rows) {
  if (wall_rows.size() != walls_.size())
    throw std::logic_error("replace_body: " + std::to_string(wall_rows.size()) + " wall archives for " + std::to_string(walls_.size()) + " walls");
  ids_.clear();
  for (const std::int64_t id : particles.id)
    if (!ids_.insert(id).second) throw std::logic_error("replace_body: particle id " + std::to_string(id) + " given twice");
  particles_ = std::move(particles);
  seeded_pairs_ = std::move(pairs);
  seeded_walls_ = std::move(wall_rows);
  pairs_ = PairContacts{};
  for (auto& w : wall_contacts_) w = WallContacts{};
  critical_step_.reset();
  stale_ = true;
}

Simulation::Places Simulation::places() const {
  Places now;
  std::vector<std::uint32_t> by_id(particles_.size());
  std::iota(by_id.begin(), by_id.end(), 0U);
  std::sort(by_id.begin(), by_id.end(), [&](std::uint32_t a, std::uint32_t b) { return particles_.id[a] < particles_.id[b]; });
  for (const std::uint32_t i : by_id) {
    now.id.push_back(particles_.id[i]);
    now.position.push_back(particles_.position[i]);
  }
  for (const Wall& w : walls_) now.wall_vertices.push_back(w.vertices);
  now.wall_travel = max_wall_displacement_;
  now.affine_approach = affine_approach_;
  return now;
}

Simulation::Places Simulation::move_to_references() {
  Places now = places();
  if (reference_positions_.size() != particles_.size() || reference_vertices_.size() != walls_.size())
    throw std::logic_error("move_to_references: the body changed since its last rebuild");
  particles_.position = reference_positions_;
  for (std::size_t w = 0; w < walls_.size(); ++w) walls_[w].vertices = reference_vertices_[w];
  repeat_last_search();
  return now;
}

void Simulation::put_back(const Places& places) {
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const auto found = std::lower_bound(places.id.begin(), places.id.end(), particles_.id[i]);
    if (found == places.id.end() || *found != particles_.id[i]) throw std::logic_error("put_back: particle " + std::to_string(particles_.id[i]) + " has no place");
    particles_.position[i] = places.position[std::size_t(found - places.id.begin())];
  }
  for (std::size_t w = 0; w < walls_.size(); ++w) walls_[w].vertices = places.wall_vertices.at(w);
  max_wall_displacement_ = places.wall_travel;
  affine_approach_ = places.affine_approach;
}

void Simulation::replace_body_at_references(ParticleStore at_reference, HistoryArchive pairs, std::vector<HistoryArchive> wall_rows,
                                            const Places& now, std::size_t rebuilds) {
  if (reference_vertices_.size() != walls_.size()) throw std::logic_error("replace_body_at_references: no rebuild to return to");
  for (std::size_t w = 0; w < walls_.size(); ++w) walls_[w].vertices = reference_vertices_[w];
  replace_body(std::move(at_reference), std::move(pairs), std::move(wall_rows));
  repeat_last_search();
  rebuild();
  put_back(now);
  rebuilds_ = rebuilds;
}

void Simulation::rebuild_if_stale() {
  if (stale_) rebuild();
}

bool Simulation::verlet_skin_used_up(double max_particle_displacement) const noexcept {
  // Two particles approach by at most 2 max|dx|, a particle and a facet by
  // max|dx| + max|dx_wall|; either must stay below the skin.
  return 2.0 * max_particle_displacement + affine_approach_ >= skin_ || max_particle_displacement + max_wall_displacement_ >= skin_;
}

void Simulation::rebuild() {
  const SearchRadii radii = search_radii();
  const double r_max = radii.r_max;
  r_max_ = r_max;
  skin_ = radii.skin;
  if (cell_)
    for (auto& x : particles_.position) x = cell_->wrap(x);  // history is keyed by ids: wrapping keeps it

  // 1. Keep the history of current contacts: by slot where the particles are
  // those of the last rebuild (the lists then hold their pairs), else under
  // stable keys (a seeded body, particles added or removed, a resumed state).
  const bool by_slot = !seeded_pairs_ && !pairs_.history.empty() && particles_.id == ids_at_rebuild_;
  PairContacts previous;
  std::optional<HistoryArchive> pair_archive;
  if (by_slot) previous = std::move(pairs_);
  else pair_archive = seeded_pairs_ ? std::move(*seeded_pairs_) : archive_history(pairs_, particles_);
  pairs_ = PairContacts{};
  seeded_pairs_.reset();
  std::vector<HistoryArchive> wall_archives;
  if (seeded_walls_) wall_archives = std::move(*seeded_walls_);
  else
    for (const auto& wc : wall_contacts_) wall_archives.push_back(archive_history(wc, particles_));
  seeded_walls_.reset();

  // 2. Cell grid; re-sort the particles by cell so that neighbours share cache lines,
  // in the canonical order (neighbour_search.hpp).
  const bool install = radii.install, join = radii.join;
  const double search = radii.search;
  last_search_ = search;
  repeat_search_.reset();
  std::vector<std::uint32_t> order;
  if (cell_) check_cell_width(2.0 * r_max + search);
  const CellGrid grid = cell_ ? build_cell_grid(particles_, 2.0 * r_max + search, *cell_, threads_, order)
                              : build_cell_grid(particles_, 2.0 * r_max + search, threads_, order, body_bounds_ ? &*body_bounds_ : nullptr);
  cell_size_ = grid.cell_size;
  particles_.permute(order, threads_);
  work_progress::advance();  // each phase of a large body's rebuild may take a while: progress between them

  // 3. New candidate lists, with the archived history.
  find_pair_candidates(grid, particles_, search, threads_, pairs_.first, pairs_.second);
  work_progress::advance();
  // Orient every pair by id so that its history is independent of slot order.
  const auto searched = std::int64_t(pairs_.size());
#pragma omp parallel for schedule(static) num_threads(threads_) if(searched >= min_parallel_items)
  for (std::int64_t i = 0; i < searched; ++i) {
    const auto k = std::size_t(i);
    if (particles_.id[pairs_.first[k]] > particles_.id[pairs_.second[k]]) std::swap(pairs_.first[k], pairs_.second[k]);
  }
  pairs_.set_strides(settings_.particle_law.history_size(), settings_.particle_law.cold_history_size());
  if (by_slot) {
    const std::vector<std::uint32_t> old_to_new = inverse_order(order, threads_);
    std::vector<std::uint32_t> match = match_previous_pairs(previous, old_to_new, pairs_.first, pairs_.second, threads_);
    if (settings_.particle_law.bonded()) append_unmatched_bonds(previous, old_to_new, match);
    pairs_.resize_history();  // uninitialised: the threads write (and first touch) every row
    move_matched_rows(std::move(previous), match, pairs_, threads_);
  } else {
    if (settings_.particle_law.bonded()) append_persistent_pairs(*pair_archive);
    pairs_.resize_history();  // uninitialised: the threads write (and first touch) every row
    restore_history(pairs_, particles_, *pair_archive, threads_);
    pair_archive.reset();  // its rows are in the lists now: not held through the rest of the rebuild
  }
  assign_pair_laws();
  if (install) install_bonds(false);
  if (join) install_bonds(true);
  if (search > skin_) drop_pairs_beyond_skin();
  compute_pair_constants();
  work_progress::advance();

  bool with_couple = settings_.particle_law.has_couple();
  std::size_t offset = pairs_.size();
  wall_offsets_.clear();
  std::vector<const WallContacts*> wall_lists;
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const auto candidates = find_facet_candidates(grid, particles_, walls_[w], skin_, r_max, threads_);
    wall_contacts_[w].assign(candidates, walls_[w].law.history_size());
    restore_history(wall_contacts_[w], particles_, wall_archives[w], threads_);
    wall_offsets_.push_back(offset);
    offset += wall_contacts_[w].size();
    wall_lists.push_back(&wall_contacts_[w]);
    with_couple = with_couple || walls_[w].law.has_couple();
  }
  outputs_.resize(offset, with_couple, cell_ ? pairs_.size() : 0);
  // One range of the pair loop per thread where the loop runs in parallel.
  const std::size_t pair_chunks = std::int64_t(pairs_.size()) >= min_parallel_items ? std::size_t(threads_) : 1;
  incidence_ = build_incidence(particles_.size(), pairs_, wall_lists, wall_offsets_, pair_chunks);

  reference_positions_ = particles_.position;
  reference_vertices_.clear();
  for (const auto& w : walls_) reference_vertices_.push_back(w.vertices);
  max_wall_displacement_ = 0.0;
  affine_approach_ = 0.0;
  ids_at_rebuild_ = particles_.id;
  stale_ = false;
  ++rebuilds_;
  work_progress::advance();  // a rebuild of a large body may take longer than a step
}

void Simulation::append_unmatched_bonds(const PairContacts& before, std::span<const std::uint32_t> old_to_new, std::vector<std::uint32_t>& match) {
  // On every thread: one row load per previous pair, a cache miss each in a
  // large model. Each previous pair is matched at most once (distinct writes),
  // and the unmatched bonds are sorted by their (unique) keys below, so the
  // order in which the threads find them does not matter.
  std::vector<char> matched(before.size(), 0);
  const auto searched = std::int64_t(match.size());
#pragma omp parallel for schedule(static) num_threads(threads_) if(searched >= min_parallel_items)
  for (std::int64_t k = 0; k < searched; ++k)
    if (match[std::size_t(k)] != no_previous_pair) matched[match[std::size_t(k)]] = 1;
  std::vector<std::pair<HistoryArchive::Key, std::uint32_t>> unmatched;
  const auto previous = std::int64_t(before.size());
#pragma omp parallel num_threads(threads_) if(previous >= min_parallel_items)
  {
    std::vector<std::pair<HistoryArchive::Key, std::uint32_t>> found;
#pragma omp for schedule(static) nowait
    for (std::int64_t i = 0; i < previous; ++i) {
      const auto k = std::size_t(i);
      if (!matched[k] && before.history[k * before.stride + bond_state_column] != 0.0)
        found.push_back({{particles_.id[old_to_new[before.first[k]]], particles_.id[old_to_new[before.second[k]]]}, std::uint32_t(k)});
    }
#pragma omp critical(dfc_unmatched_bonds)
    unmatched.insert(unmatched.end(), found.begin(), found.end());
  }
  // In key order after the searched pairs, as append_persistent_pairs appends them.
  std::sort(unmatched.begin(), unmatched.end());
  for (const auto& [key, k] : unmatched) {
    pairs_.first.push_back(old_to_new[before.first[k]]);
    pairs_.second.push_back(old_to_new[before.second[k]]);
    match.push_back(k);
  }
}

void Simulation::append_persistent_pairs(const HistoryArchive& archive) {
  const auto bonded = archive.keys_with_nonzero(bond_state_column);
  if (bonded.empty()) return;
  std::vector<HistoryArchive::Key> found(pairs_.size());
  for (std::size_t k = 0; k < pairs_.size(); ++k) found[k] = {particles_.id[pairs_.first[k]], particles_.id[pairs_.second[k]]};
  std::sort(found.begin(), found.end());
  std::vector<std::pair<std::int64_t, std::uint32_t>> slot_of(particles_.size());
  for (std::size_t i = 0; i < particles_.size(); ++i) slot_of[i] = {particles_.id[i], std::uint32_t(i)};
  std::sort(slot_of.begin(), slot_of.end());
  const auto slot = [&](std::int64_t id) {
    return std::lower_bound(slot_of.begin(), slot_of.end(), std::pair<std::int64_t, std::uint32_t>{id, 0})->second;
  };
  // Appended in key order after the searched pairs: the list stays deterministic.
  for (const auto& key : bonded) {
    if (std::binary_search(found.begin(), found.end(), key)) continue;
    pairs_.first.push_back(slot(key[0]));
    pairs_.second.push_back(slot(key[1]));
  }
}

void Simulation::assign_pair_laws() {
  pairs_.law_index.clear();
  if (materials_.count() == 1) return;
  pairs_.law_index.resize(pairs_.size());
  const auto n = std::int64_t(pairs_.size());
#pragma omp parallel for schedule(static) num_threads(threads_) if(n >= min_parallel_items)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto k = std::size_t(i);
    pairs_.law_index[k] = std::uint16_t(materials_.pair_index(particles_.material[pairs_.first[k]], particles_.material[pairs_.second[k]]));
  }
}

void Simulation::drop_pairs_beyond_skin() {
  const PeriodicSpace space = cell_ ? PeriodicSpace(*cell_) : PeriodicSpace();  // no cell: the plain difference
  const bool laws = !pairs_.law_index.empty();
  // Pair k moves to slot kept <= k: rows only ever move down, onto one already moved or dropped.
  std::size_t kept = 0;
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const std::uint32_t i = pairs_.first[k], j = pairs_.second[k];
    // A bond, intact or broken, stays a candidate however far apart (append_unmatched_bonds).
    if (pairs_.row(k)[bond_state_column] == 0.0 &&
        !within_skin(space.branch(particles_.position[i], particles_.position[j]), particles_.radius[i], particles_.radius[j], skin_))
      continue;
    if (kept != k) {
      pairs_.first[kept] = i;
      pairs_.second[kept] = j;
      if (laws) pairs_.law_index[kept] = pairs_.law_index[k];
      pairs_.move_row(k, kept);
    }
    ++kept;
  }
  pairs_.first.resize(kept);
  pairs_.second.resize(kept);
  if (laws) pairs_.law_index.resize(kept);
  pairs_.history.resize(kept * pairs_.stride);
  pairs_.cold_history.resize(kept * pairs_.cold_stride);
}

void Simulation::install_bonds(bool across_materials_only) {
  const PeriodicSpace space = cell_ ? PeriodicSpace(*cell_) : PeriodicSpace();  // no cell: the plain difference
  const double single_gap = materials_.pair_setting(0).bond_gap();
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const std::uint32_t i = pairs_.first[k], j = pairs_.second[k];
    if (across_materials_only) {
      if (particles_.material[i] == particles_.material[j] || !pairs_.whole_row_is_zero(k)) continue;
    }
    const double gap = pairs_.law_index.empty() ? single_gap : materials_.pair_setting(pairs_.law_index[k]).bond_gap();
    const double radii = particles_.radius[i] + particles_.radius[j];
    const double surface_gap = norm(space.branch(particles_.position[i], particles_.position[j])) - radii;
    // A touching pair is bonded whatever its size: |x_j - x_i| - r_i - r_j of
    // spheres placed exactly in contact is a few ulps either side of 0, so
    // the gap allows bonding_round_off (r_i + r_j) on top of bond_gap_m.
    if (surface_gap <= gap + bonding_round_off * radii) set_bond_state(pairs_.row(k), BondState::intact);
  }
  if (across_materials_only) return;  // the flag stays until the seam balance of the next step
  bonds_installed_ = true;
  install_requested_ = false;
}

BondCounts Simulation::bond_counts() const noexcept {
  BondCounts c;
  if (!settings_.particle_law.bonded() || pairs_.stride == 0) return c;
  // Every coupled advance reports these (dem_backend.cpp monitors); one load
  // per pair row, a cache miss each in a large model (2.6 million rows in the
  // paper model), so the scan runs on every thread. Integer counts: the same
  // whatever the thread count.
  std::int64_t intact = 0, damaged = 0, broken_tension = 0, broken_shear = 0;
  const auto n = std::int64_t(pairs_.size());
  const double* rows = pairs_.history.data();
  const std::size_t stride = pairs_.stride;
#pragma omp parallel for schedule(static) num_threads(threads_) if(n >= min_parallel_items) reduction(+ : intact, damaged, broken_tension, broken_shear)
  for (std::int64_t k = 0; k < n; ++k) {
    switch (bond_state(rows + std::size_t(k) * stride)) {
      case BondState::intact: ++intact; break;
      case BondState::damaged: ++damaged; break;
      case BondState::broken_tension: ++broken_tension; break;
      case BondState::broken_shear: ++broken_shear; break;
      case BondState::none: break;
    }
  }
  c.intact = intact;
  c.damaged = damaged;
  c.broken_tension = broken_tension;
  c.broken_shear = broken_shear;
  return c;
}

void Simulation::move_walls(double dt) {
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    Wall& wall = walls_[w];
    for (std::size_t v = 0; v < wall.vertex_count(); ++v) {
      wall.vertices[v] += dt * wall.vertex_velocity[v];
      max_wall_displacement_ = std::max(max_wall_displacement_, norm(wall.vertices[v] - reference_vertices_[w][v]));
    }
  }
}

const ContactOutputs& Simulation::contact_outputs() const {
  if (!outputs_complete_) throw std::logic_error("contact outputs read after a step that recorded only the gathered ones (ContactRecord::gathered_only)");
  return outputs_;
}

void Simulation::prepare_step(double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw UserError("the time step must be a positive number of seconds");
  if (stale_) rebuild();
  for (auto& wall : walls_)
    if (wall.motion == WallMotion::prescribed)
      std::fill(wall.vertex_velocity.begin(), wall.vertex_velocity.end(), step_ >= wall.start_step ? wall.prescribed_velocity : Vec3{});
  if (join_materials_requested_) balance_seams(dt);
}

void Simulation::step(double dt, ContactRecord record) {
  prepare_step(dt);
  outputs_complete_ = record == ContactRecord::complete;
  if (compute_contact_forces(dt, record)) {
    std::ostringstream msg;
    msg << "a contact overlap exceeded " << settings_.max_overlap_fraction << " of the smaller particle radius at step " << step_ << " ("
        << describe_largest_overlap() << "): the run is unstable; use a time step below the critical " << critical_timestep()
        << " s (or a smaller fraction of it), softer contacts or slower walls; a slow contact (small speeds) between spheres of very"
           " different sizes may instead carry its load at that overlap: then raise timestep.max_overlap_fraction (at most 1)";
    throw SolverError(msg.str());
  }
  if (settings_.local_damping != 0.0) damping_force_.resize(particles_.size());
  const MotionReport motion =
      integrate_motion(particles_, incidence_, outputs_, reference_positions_, {dt, settings_.gravity, settings_.local_damping, damping_force_}, threads_);
  if (!motion.finite)
    throw SolverError("a particle position or velocity became non-finite at step " + std::to_string(step_) +
                      ": the run is unstable; reduce the time step");
  for (std::size_t w = 0; w < walls_.size(); ++w) distribute_wall_forces(walls_[w], wall_contacts_[w], outputs_, wall_offsets_[w]);
  move_walls(dt);
  if (cell_) {
    // The reference positions deform too, so max|dx| stays the motion relative
    // to the homogeneous flow; the flow itself brings two partners (centres at
    // most 2 r_max + skin apart) closer by at most max_a |rate_a dt| times that.
    const Vec3 r = cell_->strain_rate;
    affine_approach_ += std::max({std::abs(r.x), std::abs(r.y), std::abs(r.z)}) * dt * (2.0 * r_max_ + skin_);
    cell_->deform(dt, particles_.position, reference_positions_, threads_);
  }
  ++step_;
  work_progress::advance();  // the heartbeat's proof that the main thread works (SPEC.md §9.1)

  if (verlet_skin_used_up(std::sqrt(motion.max_displacement2))) stale_ = true;
}

void Simulation::set_local_damping(double alpha) {
  if (!(alpha >= 0.0 && alpha < 1.0)) throw UserError("local damping must be in [0, 1)");
  settings_.local_damping = alpha;
  if (alpha == 0.0) damping_force_.clear();  // undamped steps store no damping force: the total is 0, not the last damped step's
}

Vec3 Simulation::damping_force_total() const {
  // Every step (the force balance averages it over an advance): the blocked
  // fixed order, about 1 ns a term, not the exact sum of the monitors (2-4 ns).
  return fixed_order_sum<Vec3>(damping_force_.size(), threads_, [&](std::size_t i) { return damping_force_[i]; });
}

Vec3 Simulation::momentum() const {
  return exact_vec3_sum(particles_.size(), threads_, [&](std::size_t i) { return particles_.mass[i] * particles_.velocity[i]; });
}

void Simulation::run(std::int64_t steps, double dt) {
  const double limit = critical_timestep();
  if (dt > limit) {
    std::ostringstream msg;
    msg << "time step " << dt << " s exceeds the critical time step " << limit << " s of this packing and its contact stiffnesses; use at most "
        << limit << " s (a fraction such as 0.2 of it is safer in dense packings)";
    throw SolverError(msg.str());
  }
  for (std::int64_t s = 0; s < steps; ++s) step(dt, s + 1 < steps ? ContactRecord::gathered_only : ContactRecord::complete);
}

}  // namespace dfc::dem
