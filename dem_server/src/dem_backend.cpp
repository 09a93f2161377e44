#include "dfc/dem/dem_backend.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <iostream>
#include <sstream>

#include "dfc/common/errors.hpp"
#include "dfc/common/unstable_step_error.hpp"
#include "dfc/common/version.hpp"
#include "dfc/dem/measurements.hpp"
#include "dfc/dem/particle_stress.hpp"
#include "dfc/dem/region_config.hpp"
#include "dfc/dem/snapshot_pairs.hpp"
#include "dfc/protocol/monitor_units.hpp"
#include "dfc/protocol/progress_monitors.hpp"

namespace dfc::dem {

namespace {

nlohmann::json to_json(const Vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

std::vector<double> flatten(std::span<const Vec3> v) {
  std::vector<double> out;
  out.reserve(3 * v.size());
  for (const auto& x : v) out.insert(out.end(), {x.x, x.y, x.z});
  return out;
}

/// Height of a profile slice: one REV cell of the coarsest zone. A slice
/// spans the whole cross-section, so its coarsest spheres set how many layers
/// it averages; slices one fine cell high hold three layers of the S = 4.8
/// spheres in the paper's graded model and scatter by up to 14 % (measured;
/// docs/dem_generation.md §6), one coarse cell by under 6 %.
double profile_slice_height(const PcrmConfig& pcrm) {
  double coarsest = pcrm.scale_factor;
  for (const PcrmZone& zone : pcrm.zones) coarsest = std::max(coarsest, zone.scale_factor);
  return pcrm.rev.cell.length().z * coarsest / pcrm.scale_factor;
}

/// Stress profile of a generated body over horizontal slices
/// (profile_slice_height; particle_stress.hpp), top first: depth below the
/// surface, sigma_v, sigma_h, the achieved K0 = sigma_h / sigma_v; the sides
/// moved in by two largest diameters (the boundary layer). With the profile
/// the body was generated for (`target`), a line on stderr gives each slice's
/// errors and achieved K0, and says so when an interior slice (not the top or
/// bottom one) is more than 5 % off: a body that is not at the geostatic state
/// asked for is never left unsaid (docs/dem_generation.md, "Changing the g-level").
/// `body`: the whole body's particles, `stress` their particle_stress (one
/// row each), `steps` the steps taken.
void append_profile_arrays(const ParticleStore& body, std::span<const Stress6> stress, std::int64_t steps, const PcrmConfig& pcrm,
                           const StressProfile* target, std::vector<protocol::Array>& arrays) {
  const auto [lo, hi] = region_bounds(pcrm.region);
  const int slices = std::max(1, int(std::lround((hi.z - lo.z) / profile_slice_height(pcrm))));
  const SliceProfile profile = slice_profile(body.position, body.radius, stress, pcrm.region, slices, 4.0 * largest_radius(body));
  std::vector<double> depth, k0;
  for (std::size_t k = 0; k < profile.z.size(); ++k) {
    depth.push_back(pcrm.profile.surface_z - profile.z[k]);
    k0.push_back(profile.sigma_v[k] != 0.0 ? profile.sigma_h[k] / profile.sigma_v[k] : 0.0);
  }
  const auto k = std::int64_t(depth.size());
  arrays.push_back(protocol::Array::from_f64("profile_depth_m", {k}, depth));
  arrays.push_back(protocol::Array::from_f64("profile_sigma_v_pa", {k}, profile.sigma_v));
  arrays.push_back(protocol::Array::from_f64("profile_sigma_h_pa", {k}, profile.sigma_h));
  arrays.push_back(protocol::Array::from_f64("profile_k0", {k}, k0));
  arrays.push_back(protocol::Array::from_f64("profile_porosity", {k}, profile.porosity));
  if (target == nullptr || steps == 0) return;  // no contact force is known before the first step
  std::ostringstream line;
  line.precision(3);
  double worst = 0.0;
  for (std::size_t j = 0; j < depth.size(); ++j) {
    const double v = target->vertical(profile.z[j]), h = target->horizontal(profile.z[j]);
    const double ev = profile.sigma_v[j] / v - 1.0, eh = profile.sigma_h[j] / h - 1.0;
    if (j > 0 && j + 1 < depth.size()) worst = std::max({worst, std::abs(ev), std::abs(eh)});
    line << (j == 0 ? "" : "; ") << 1e3 * depth[j] << " mm: sigma_v " << 100.0 * ev << " %, sigma_h " << 100.0 * eh << " %, K0 " << k0[j];
  }
  std::cerr << "dem_server: generated body at step " << steps << ", stress per slice one REV cell high against gamma z and K0 gamma z (K0 "
            << target->k0 << " asked): " << line.str() << std::endl;
  if (worst > 0.05)
    std::cerr << "dem_server: warning: at step " << steps << " an interior slice of the generated body is " << 100.0 * worst
              << " % off the geostatic state asked for (more than 5 %); the achieved K0 per slice is the snapshot's profile_k0" << std::endl;
}

/// The particle arrays every snapshot holds (SPEC.md §6.4), in the order of
/// `p`, and each particle's zone where the body is graded.
void append_particle_arrays(const ParticleStore& p, bool graded, std::vector<protocol::Array>& arrays) {
  const auto n = std::int64_t(p.size());
  arrays.push_back(protocol::Array::from_f64("particle_position", {n, 3}, flatten(p.position)));
  arrays.push_back(protocol::Array::from_f64("particle_radius", {n}, p.radius));
  arrays.push_back(protocol::Array::from_f64("particle_velocity", {n, 3}, flatten(p.velocity)));
  arrays.push_back(protocol::Array::from_i64("particle_id", {n}, p.id));
  if (graded) {  // graded bodies only: the zone (material) of each particle
    const std::vector<std::int64_t> material(p.material.begin(), p.material.end());
    arrays.push_back(protocol::Array::from_i64("particle_material", {n}, material));
  }
}

/// The walls' triangles (none without walls).
void append_wall_arrays(const std::vector<Wall>& walls, std::vector<protocol::Array>& arrays) {
  if (walls.empty()) return;
  std::vector<Vec3> vertices;
  std::vector<std::int64_t> facets, facet_wall;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const Wall& wall = walls[w];
    const auto offset = std::int64_t(vertices.size());
    vertices.insert(vertices.end(), wall.vertices.begin(), wall.vertices.end());
    for (const auto& f : wall.facets) {
      for (const auto v : f) facets.push_back(offset + std::int64_t(v));
      facet_wall.push_back(std::int64_t(w));
    }
  }
  arrays.push_back(protocol::Array::from_f64("wall_vertices", {std::int64_t(vertices.size()), 3}, flatten(vertices)));
  arrays.push_back(protocol::Array::from_i64("wall_facets", {std::int64_t(facets.size() / 3), 3}, facets));
  // Which wall each facet is (its index in the DEM's wall list, the order of
  // the wall_<name> monitors): ParaView thresholds on it to show the pile alone.
  arrays.push_back(protocol::Array::from_i64("wall_facet_wall", {std::int64_t(facet_wall.size())}, facet_wall));
}

/// Per-particle Love–Weber stress (particle_stress.hpp) as particle_stress_pa:
/// stress profiles and maps come from the file; ParaView shows it as a
/// Tensor6 on the particles.
void append_stress_array(std::span<const Stress6> stress, std::vector<protocol::Array>& arrays) {
  std::vector<double> flat;
  flat.reserve(6 * stress.size());
  for (const Stress6& v : stress) flat.insert(flat.end(), v.begin(), v.end());
  arrays.push_back(protocol::Array::from_f64("particle_stress_pa", {std::int64_t(stress.size()), 6}, flat));
}

/// particle_stress of the whole body in particle id order, on rank 0 (empty
/// elsewhere; collective): each process's owned particles, whose partners
/// it all holds, so their rows have the bits of the body on one process.
std::vector<Stress6> gathered_particle_stress(const DemEngine& engine) {
  const Simulation& part = engine.part();
  const std::vector<Stress6> local = particle_stress(part);
  std::vector<double> mine;
  for (std::size_t i = 0; i < local.size(); ++i) {
    if (!engine.owns(i)) continue;
    mine.push_back(std::bit_cast<double>(part.particles().id[i]));  // the id's bits, exact
    mine.insert(mine.end(), local[i].begin(), local[i].end());
  }
  const std::vector<double> all = engine.gather_on_root(mine);
  std::vector<std::pair<double, Stress6>> rows(all.size() / 7);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    rows[r].first = all[7 * r];
    std::copy_n(all.begin() + std::ptrdiff_t(7 * r + 1), 6, rows[r].second.begin());
  }
  const auto id_of = [](const auto& row) { return std::bit_cast<std::int64_t>(row.first); };
  std::sort(rows.begin(), rows.end(), [&](const auto& a, const auto& b) { return id_of(a) < id_of(b); });
  std::vector<Stress6> out;
  out.reserve(rows.size());
  for (const auto& row : rows) out.push_back(row.second);
  return out;
}

/// Every process's `rows` on rank 0, ordered by their ids (empty elsewhere; collective).
PairRows gathered_pair_rows(const DemEngine& engine, const PairRows& rows) {
  PairRows all{.width = rows.width, .values = engine.gather_on_root(rows.values)};
  sort_by_ids(all);
  return all;
}

/// The local-damping forces of the last step over the slots `engine` owns,
/// added exactly to `sums` (an advance's total: the same bits for any
/// process or thread count).
void add_damping_forces(const DemEngine& engine, std::array<ExactSum, 3>& sums) {
  const Simulation& s = engine.part();
  const std::span<const Vec3> damping = s.damping_forces();
  if (damping.empty()) return;
  const auto owned = engine.owned();
  const auto step = exact_accumulators<3>(damping.size(), s.threads(), [&](std::size_t i) {
    if (!owned.empty() && owned[i] == 0) return std::array<double, 3>{};
    return std::array<double, 3>{damping[i].x, damping[i].y, damping[i].z};
  });
  for (std::size_t k = 0; k < 3; ++k) sums[k] += step[k];
}

}  // namespace

DemBackend::DemBackend(std::function<std::unique_ptr<DemEngine>(Simulation&)> make_engine, int processes, int rank)
    : make_engine_(std::move(make_engine)), processes_(processes), rank_(rank) {}


protocol::SolverIdentity DemBackend::identity() const {
  return {"dem_server", std::string(project_version()), "dem",
          {protocol::capability::accepts_interface, protocol::capability::snapshot, protocol::capability::checkpoint}};
}

nlohmann::json DemBackend::configure(const nlohmann::json& section) {
  DemConfig config = parse_dem_config(section);
  DemModel model = build_model(config);
  engine_.reset();  // it refers to the model replaced now
  config_ = std::move(config);
  model_ = std::move(model);
  interface_wall_.reset();
  generation_removed_by_interface_ = 0;
  averages_ = nlohmann::json::object();
  stepper_ = nullptr;  // a servo-controlled experiment steps the simulation itself
  for (const auto& protocol : model_.loading)
    if (protocol->drives_step()) stepper_ = protocol.get();
  nlohmann::json info = {{"dt_suggested", model_.dt},
                         {"dt_max", model_.dt_critical},
                         {"particles", sim().particles().size()},
                         {"particles_removed_by_walls", model_.removed_particles},
                         {"contact_law", config_.contact.info->keyword}};
  // The walls by name in the order of a snapshot's wall_facet_wall index (a
  // coupled run adds the coupling surface after them, set_interface_mesh).
  info["walls"] = nlohmann::json::array();
  for (const Wall& wall : sim().walls()) info["walls"].push_back(wall.name);
  if (const auto& gen = model_.generation) {
    info["generation"] = {{"rev_particles", gen->rev.spheres.size()},
                          {"rev_bonds", gen->rev.bonds},
                          {"rev_damaged_bonds", gen->rev.damaged_bonds},
                          {"rev_porosity", gen->rev.porosity},
                          {"rev_stress_pa", to_json(gen->rev.stress)},
                          {"rev_steps", gen->rev.steps},
                          {"copies", gen->body.copies},
                          {"unit_weight_n_m3", gen->profile.unit_weight},
                          {"k0", gen->profile.k0},
                          {"surface_z_m", gen->profile.surface_z},
                          {"surcharge_pa", gen->profile.surcharge},
                          {"scaled_bonds", gen->scaling.scaled_bonds},
                          {"lambda_min", gen->scaling.lambda_min},
                          {"lambda_max", gen->scaling.lambda_max}};
    if (const auto& pcrm = config_.particles.pcrm; pcrm && !pcrm->zones.empty()) {
      nlohmann::json zones = nlohmann::json::array();
      for (std::size_t k = 0; k < pcrm->zones.size(); ++k)
        zones.push_back({{"material", k}, {"scale_factor", pcrm->zones[k].scale_factor}, {"particles", gen->zone_spheres[k]}});
      info["generation"]["zones"] = zones;
      info["generation"]["seam_removed"] = gen->seam_removed;
      info["generation"]["seam_seated"] = gen->seam_seated;
    }
  }
  if (const auto& prep = model_.preparation) {
    nlohmann::json p = {{"consolidated", prep->consolidated},
                        {"consolidation_steps", prep->consolidation_steps},
                        {"stress_relative_error", prep->stress_error},
                        {"stress_pa", to_json(prep->stress)},
                        {"porosity", prep->porosity},
                        {"bonds_installed", prep->bonds_installed}};
    if (prep->expansion) {
      p["porosity_after_expansion"] = prep->expansion->porosity_geometric;
      p["expansion_steps"] = prep->expansion->steps;
    }
    info["preparation"] = p;
  }
  info[protocol::monitor_units_key] = monitor_units();
  if (processes_ > 1) info["processes"] = processes_;
  nlohmann::json progress = nlohmann::json::array();
  for (const auto& protocol : model_.loading) protocol->progress_monitors(progress);
  if (!progress.empty()) info[protocol::progress_monitors_key] = protocol::to_json(protocol::parse_progress_monitors({{protocol::progress_monitors_key, progress}}));
  return info;
}

nlohmann::json DemBackend::monitor_units() const {
  using namespace protocol::unit;
  // Every monitor monitors() may send, whatever the section enables: declaring
  // one that a run never sends is allowed (SPEC.md §6.3) and keeps this list
  // free of the conditions that choose which ones are sent.
  nlohmann::json units = protocol::shared_monitor_units();
  for (const char* count : {"particle_count", "contact_count", "coordination_number", "bonds_intact", "bonds_damaged",
                            "bonds_broken_tension", "bonds_broken_shear"})
    units[count] = dimensionless;
  units["total_weight_n"] = newton;
  units["damping_force_n"] = newton;
  units["particle_momentum_n_s"] = newton_second;
  units["dt_critical_s"] = second;
  for (const LoadingProtocolEntry& entry : loading_protocol_registry()) entry.declare_monitors(units);
  for (const Wall& wall : simulation().walls()) {
    units["wall_" + wall.name + "_force_n"] = newton;
    units["wall_" + wall.name + "_moment_nm"] = newton_metre;
  }
  return units;
}

Simulation& DemBackend::sim() {
  if (!model_.simulation) throw protocol::ProtocolError(protocol::ErrorCode::out_of_order, "the DEM is not configured yet; send configure first");
  return *model_.simulation;
}

DemEngine& DemBackend::engine() {
  Simulation& s = sim();
  if (!engine_) engine_ = make_engine_(s);
  return *engine_;
}

const Simulation& DemBackend::simulation() const {
  if (!model_.simulation) throw protocol::ProtocolError(protocol::ErrorCode::out_of_order, "the DEM is not configured yet; send configure first");
  return *model_.simulation;
}

void DemBackend::set_interface(const protocol::InterfaceMesh& mesh) {
  using protocol::ErrorCode;
  using protocol::ProtocolError;
  Simulation& s = sim();
  const std::int64_t n = mesh.node_count();
  if (std::int64_t(mesh.coordinates.size()) != 3 * n)
    throw ProtocolError(ErrorCode::bad_array, "interface coordinates must be f64 [" + std::to_string(n) + ",3], one row per node id");
  if (mesh.facets.size() % 3 != 0 || mesh.facets.empty())
    throw ProtocolError(ErrorCode::bad_array, "interface facets must be a non-empty i64 [m,3] array of node rows");
  WallMesh wall_mesh;
  for (std::int64_t v = 0; v < n; ++v)
    wall_mesh.vertices.push_back({mesh.coordinates[std::size_t(3 * v)], mesh.coordinates[std::size_t(3 * v + 1)], mesh.coordinates[std::size_t(3 * v + 2)]});
  for (std::size_t f = 0; f < mesh.facets.size(); f += 3) {
    Facet facet{};
    for (std::size_t k = 0; k < 3; ++k) {
      const std::int64_t row = mesh.facets[f + k];
      if (row < 0 || row >= n)
        throw ProtocolError(ErrorCode::bad_array, "interface facet " + std::to_string(f / 3) + " refers to node row " + std::to_string(row) +
                                                      " but there are " + std::to_string(n) + " nodes");
      facet[k] = std::uint32_t(row);
    }
    wall_mesh.facets.push_back(facet);
  }
  Wall wall;
  try {
    wall = make_wall("interface", std::move(wall_mesh), WallMotion::coupling, config_.wall_contact);
  } catch (const UserError& e) {
    throw ProtocolError(ErrorCode::bad_array, e.what());
  }
  // A generated body (generator "pcrm") is trimmed to the region's circle or
  // box; the continuum's facets lie inside it (a polygon inscribed in the
  // cavity), so spheres they cut are removed now, before the first step, by
  // the same rule as the rigid walls (docs/dem_generation.md §2).
  if (const auto& pcrm = config_.particles.pcrm; pcrm && s.step_count() == 0) {
    const std::size_t seated_before = model_.generation->seated;
    generation_removed_by_interface_ += fit_to_wall(s, wall, *pcrm, *model_.generation);
    const std::size_t seated = model_.generation->seated - seated_before;
    std::cerr << "dem_server: pcrm coupling wall: " << generation_removed_by_interface_ << " spheres it cut removed, " << seated
              << " seated on it; " << s.particles().size() << " spheres in the model" << std::endl;
  }
  if (engine_ && processes_ > 1 && s.step_count() > 0)
    throw ProtocolError(ErrorCode::unsupported, "set_interface after the first advance is not supported on more than one process");
  engine_.reset();  // made again at the next advance, from the body the coupling wall has trimmed
  if (interface_wall_) s.replace_wall(*interface_wall_, std::move(wall));
  else interface_wall_ = s.add_wall(std::move(wall));
}

protocol::AdvanceResult DemBackend::advance(const protocol::AdvanceRequest& request) {
  using protocol::ErrorCode;
  using protocol::ProtocolError;
  DemEngine& e = engine();
  Simulation& s = e.part();

  // 1. Refuse an unstable step before anything changes (SPEC.md §5.2: the reply carries the largest stable one).
  const double limit = e.critical_timestep();
  if (request.dt > limit) {
    std::ostringstream msg;
    msg << "dt = " << request.dt << " s exceeds the critical time step of the DEM; the largest stable step is " << limit << " s";
    throw UnstableStepError(msg.str(), limit);
  }

  // 2. Interface velocities (required exactly when an interface exists); nothing else (SPEC.md §6.1).
  protocol::require_only(request.inputs, {protocol::field::velocity}, "dem_server");
  std::vector<Vec3> node_velocity;
  if (interface_wall_) {
    const auto n = std::int64_t(s.walls()[*interface_wall_].vertex_count());
    const std::vector<double> v = protocol::require_f64(request.inputs, protocol::field::velocity, n, 3);
    for (std::size_t k = 0; k < v.size(); k += 3) {
      node_velocity.push_back({v[k], v[k + 1], v[k + 2]});
      if (!is_finite(node_velocity.back())) throw ProtocolError(ErrorCode::bad_array, "array 'velocity' holds a non-finite value in row " + std::to_string(k / 3));
    }
    s.set_vertex_velocities(*interface_wall_, node_velocity);
  } else if (protocol::find_array(request.inputs, protocol::field::velocity) != nullptr) {
    throw ProtocolError(ErrorCode::bad_array, "advance carries 'velocity' but no interface was set; send set_interface first or omit the array");
  }


  // 3. Run, accumulating impulses of the interface, the pile and every wall.
  const auto& walls = s.walls();
  std::vector<Vec3> node_force_sum(interface_wall_ ? walls[*interface_wall_].vertex_count() : 0);
  std::vector<Vec3> wall_force_sum(walls.size()), wall_moment_sum(walls.size());
  Vec3 reaction_sum;
  std::array<ExactSum, 3> damping_sums{};
  for (const auto& protocol : model_.loading) protocol->before_advance(e, request.n_steps);
  for (std::int64_t step = 0; step < request.n_steps; ++step) {
    for (const auto& protocol : model_.loading) protocol->before_step(e);
    if (stepper_) {
      stepper_->step(e, request.dt);
    } else {
      // Only the last step's contact outputs are read (results, measurements).
      e.step(request.dt, step + 1 < request.n_steps ? ContactRecord::gathered_only : ContactRecord::complete);
    }
    for (const auto& protocol : model_.loading) protocol->after_step(e);
    add_damping_forces(e, damping_sums);
    for (std::size_t w = 0; w < walls.size(); ++w) {
      wall_force_sum[w] += walls[w].force;
      wall_moment_sum[w] += walls[w].moment;
    }
    if (interface_wall_) {
      const Wall& wall = walls[*interface_wall_];
      for (std::size_t v = 0; v < node_force_sum.size(); ++v) node_force_sum[v] += wall.vertex_force[v];
      reaction_sum += wall.force_on_particles;
    }
  }
  for (const auto& protocol : model_.loading) protocol->end_advance(e);
  e.sum_over_processes(damping_sums);
  const Vec3 damping_sum{damping_sums[0].value(), damping_sums[1].value(), damping_sums[2].value()};
  const double inv_n = 1.0 / double(request.n_steps);

  // 4. Averages (impulse / duration) and outputs.
  protocol::AdvanceResult result;
  averages_ = nlohmann::json::object();
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (interface_wall_ && w == *interface_wall_) continue;
    averages_["wall_" + walls[w].name + "_force_n"] = to_json(inv_n * wall_force_sum[w]);
    averages_["wall_" + walls[w].name + "_moment_nm"] = to_json(inv_n * wall_moment_sum[w]);
  }
  for (const auto& protocol : model_.loading) protocol->averages(e, {wall_force_sum, inv_n}, averages_);
  averages_["damping_force_n"] = to_json(inv_n * damping_sum);  // 0 when undamped: the column stays when a stage turns damping off
  if (interface_wall_) {
    double power = 0.0;
    for (std::size_t v = 0; v < node_force_sum.size(); ++v) {
      node_force_sum[v] *= inv_n;
      power += dot(node_force_sum[v], node_velocity[v]);
    }
    averages_["interface_force_reaction"] = to_json(inv_n * reaction_sum);
    averages_["interface_power_w"] = power;
    const auto rows = std::int64_t(node_force_sum.size());
    result.outputs.push_back(protocol::Array::from_f64(protocol::field::force, {rows, 3}, flatten(node_force_sum)));
  }
  result.monitors = monitors();
  return result;
}

nlohmann::json DemBackend::monitors() {
  const DemEngine& e = engine();
  const Simulation& s = e.part();
  const Measurements m = e.measure();
  nlohmann::json out = averages_;
  out["unbalanced_force_ratio"] = m.unbalanced_force_ratio;
  out["kinetic_energy_j"] = m.kinetic_energy;
  out["particle_count"] = m.particle_count;
  out["contact_count"] = m.contact_count();
  out["coordination_number"] = m.coordination_number;
  out["total_weight_n"] = m.total_weight;
  out["particle_momentum_n_s"] = to_json(e.momentum());
  out["dt_critical_s"] = e.critical_timestep();
  if (s.settings().particle_law.bonded()) {  // new monitors for bonded laws only: unbonded runs keep their exact set
    const BondCounts bonds = e.bond_counts();
    out["bonds_intact"] = bonds.intact;
    out["bonds_damaged"] = bonds.damaged;
    out["bonds_broken_tension"] = bonds.broken_tension;
    out["bonds_broken_shear"] = bonds.broken_shear;
  }
  for (const auto& protocol : model_.loading) protocol->monitors(e, out);
  return out;
}

std::vector<protocol::Array> DemBackend::snapshot(std::string& kind) {
  kind = "particles";
  if (engine().processes() > 1) return gathered_snapshot();
  const Simulation& s = sim();
  std::vector<protocol::Array> arrays;
  append_particle_arrays(s.particles(), s.materials().count() > 1, arrays);
  // The rest as the DEM section's "snapshot" block chooses (snapshot_contents.hpp).
  const SnapshotContents& contents = config_.snapshot;
  const auto& pcrm = config_.particles.pcrm;
  std::vector<Stress6> stress;
  if (contents.particle_stress || pcrm) stress = particle_stress(s);
  if (contents.particle_stress) append_stress_array(stress, arrays);
  if (contents.bonds && s.settings().particle_law.bonded()) append_bond_arrays(s, arrays);
  if (contents.contacts) append_contact_arrays(s, contents.contacts_min_force, arrays);
  if (pcrm) append_profile_arrays(s.particles(), stress, s.step_count(), *pcrm, model_.generation ? &model_.generation->profile : nullptr, arrays);
  if (contents.walls) append_wall_arrays(s.walls(), arrays);
  return arrays;
}

std::vector<protocol::Array> DemBackend::gathered_snapshot() {
  // The same arrays as one process writes, their rows in particle id order
  // (snapshot_pairs.hpp): every process sends the rows of what it owns, rank 0
  // orders them by id. Every process takes part in the gathers; rank 0 alone
  // speaks, the others' arrays are dropped.
  const DemEngine& e = engine();
  const Simulation& part = e.part();
  const SnapshotContents& contents = config_.snapshot;
  const auto& pcrm = config_.particles.pcrm;
  const ParticleStore body = e.whole_body_by_id();
  std::vector<Stress6> stress;
  if (contents.particle_stress || pcrm) stress = gathered_particle_stress(e);
  const bool bonds = contents.bonds && part.settings().particle_law.bonded();
  PairRows bond_table, contact_table;
  if (bonds) bond_table = gathered_pair_rows(e, bond_rows(part, e.owned()));
  if (contents.contacts) contact_table = gathered_pair_rows(e, contact_rows(part, contents.contacts_min_force, e.owned()));
  if (e.rank() != 0) return {};
  std::vector<protocol::Array> arrays;
  append_particle_arrays(body, part.materials().count() > 1, arrays);
  if (contents.particle_stress) append_stress_array(stress, arrays);
  const ParticleRows rows_of(body.id);
  if (bonds) append_bond_arrays(bond_table, rows_of, bond_damage_written(part), arrays);
  if (contents.contacts) append_contact_arrays(contact_table, rows_of, arrays);
  if (pcrm) append_profile_arrays(body, stress, part.step_count(), *pcrm, model_.generation ? &model_.generation->profile : nullptr, arrays);
  if (contents.walls) append_wall_arrays(part.walls(), arrays);
  return arrays;
}

}  // namespace dfc::dem
