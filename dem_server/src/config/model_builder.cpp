#include "dfc/dem/model_builder.hpp"

#include <algorithm>
#include <sstream>

#include "dfc/common/errors.hpp"
#include "dfc/dem/model_layout.hpp"
#include "dfc/dem/timestep.hpp"
#include "dfc/dem/triangle_geometry.hpp"

namespace dfc::dem {

namespace {

/// A sphere whose centre lies inside the (closed) pile: it would be trapped
/// inside the pile and load its tip from within, so it is removed like one
/// cut by a wall. The polygonal pile is inscribed in its radius, so testing
/// against the circle removes a slightly larger region — on the safe side.
/// An open tube's bore (r < inner_radius) is soil: only a centre inside the
/// tube's wall counts (spheres the wall cuts go as for any wall, fit_to_wall).
bool inside_pile(const GeneratedSphere& s, const CylinderGeometry& g) {
  const double dx = s.centre.x - g.axis_x;
  const double dy = s.centre.y - g.axis_y;
  const double r2 = dx * dx + dy * dy;
  return r2 < g.radius * g.radius && r2 >= g.inner_radius * g.inner_radius && s.centre.z > g.tip_z && s.centre.z < g.tip_z + g.length;
}

/// s, critical step of these particles with the particle, wall_contact
/// (the coupling wall arrives later but counts now) and wall laws.
double critical_step(const ParticleStore& particles, const DemConfig& c, const std::vector<Wall>& walls) {
  const auto bound = [&](double radius) {
    StiffnessBound k = stiffest(c.contact.stiffness_bound(radius), c.wall_contact.stiffness_bound(radius));
    for (const auto& m : c.material_laws) k = stiffest(k, m.stiffness_bound(radius));
    for (const auto& w : walls) k = stiffest(k, w.law.stiffness_bound(radius));
    return k;
  };
  return critical_timestep(particles, bound, c.timestep.step_bound);
}

/// Steps 3-5 of build_model after the particles: the cell, the time step
/// and the loading protocols' preparation.
DemModel finish_model(DemModel& model, const DemConfig& c, const ModelLayout& layout, bool prepared) {
  Simulation& sim = *model.simulation;
  if (sim.particles().size() == 0) throw ConfigError("particles", "every sphere overlaps a wall or the pile; nothing is left to simulate");
  if (c.periodic) {
    try {
      sim.set_periodic_cell(c.periodic->cell);
    } catch (const UserError& e) {
      throw ConfigError("periodic.max_m", e.what());
    }
  }

  // 4. Time step: the coupling wall (wall_contact) arrives later but counts now.
  model.dt_critical = critical_step(sim.particles(), c, sim.walls());
  if (c.timestep.dt) {
    if (*c.timestep.dt > model.dt_critical) {
      std::ostringstream msg;
      msg << "dt_s = " << *c.timestep.dt << " s exceeds the critical time step " << model.dt_critical
          << " s of these particles and stiffnesses; use fraction_of_critical (e.g. 0.2) or a smaller dt_s";
      throw ConfigError("timestep.dt_s", msg.str());
    }
    model.dt = *c.timestep.dt;
  } else {
    model.dt = c.timestep.fraction_of_critical * model.dt_critical;
  }

  // 5. The protocols' preparation: of a periodic REV or of a sample in six
  // walls (consolidation, confinement), and the references of every
  // protocol's monitors. The critical step above used the start radii of a
  // radius expansion; the grown packing's step is taken again, for the servo stages.
  // The servo's cap: 1e-4 strain per step unless given (a periodic cell's
  // loading needs it even without a preparation stage).
  const auto cap = [&] {
    const std::optional<double> given = c.periodic ? c.periodic->max_strain_rate : c.triaxial ? c.triaxial->max_strain_rate : std::nullopt;
    return given.value_or(1e-4 / model.dt);
  };
  model.max_strain_rate = c.periodic || c.triaxial ? cap() : 0.0;
  const double fraction = c.timestep.dt ? *c.timestep.dt / model.dt_critical : c.timestep.fraction_of_critical;
  if (prepared && c.particles.generator == "radius_expansion") {
    ParticleStore grown = sim.particles();
    for (std::size_t i = 0; i < grown.size(); ++i) grown.set_radius(i, layout.final_radius[std::size_t(grown.id[i])]);
    model.dt_critical = critical_step(grown, c, sim.walls());
    model.dt = c.timestep.dt ? std::min(*c.timestep.dt, model.dt_critical) : fraction * model.dt_critical;
    model.max_strain_rate = cap();  // of the grown packing's step
  }
  for (const auto& protocol : model.loading) protocol->prepare(model, {layout.final_radius, fraction});
  return std::move(model);
}

/// Generator "pcrm": the generated body with its bonds' state, less the
/// spheres a rigid wall or the pile cuts (and their pairs).
void add_generated_body(DemModel& model, const DemConfig& c) {
  Simulation& sim = *model.simulation;
  PcrmConfig config = *c.particles.pcrm;
  config.rev.fraction_of_critical = c.timestep.fraction_of_critical;
  model.generation = generate_pcrm(config, sim.settings(), c.gravity);
  const ReplicatedBody& body = model.generation->body;
  for (std::size_t k = 0; k < body.spheres.size(); ++k)
    sim.add_sphere(body.id[k], body.spheres[k].centre, body.spheres[k].radius, c.particles.density, body.material[k]);
  // The simulation holds the spheres now; the rows move into its seed.
  sim.seed_pair_history(model.generation->body.release_into_archive(), true);  // `body` is empty from here on
  if (!c.material_laws.empty()) sim.bond_across_materials_now();  // the seams between zones (pcrm_zones.hpp)
  const ParticleStore& p = sim.particles();
  if (c.pile)
    model.removed_particles = sim.remove_particles_before_start([&](std::size_t i) { return inside_pile({p.position[i], p.radius[i]}, c.pile->geometry); });
  for (const auto& wall : sim.walls()) model.removed_particles += fit_to_wall(sim, wall, config, *model.generation);
}

}  // namespace

DemModel build_model(const DemConfig& c) {
  DemModel model;
  // 1. Where the spheres and walls are (model_layout.hpp), arranged by the loading protocols.
  model.loading = make_loading_protocols(c);
  const ModelLayout layout = lay_out_model(c, model.loading);
  // A prepared sample is bonded after its preparation (PFC order), not at the first rebuild.
  const bool prepared = std::any_of(model.loading.begin(), model.loading.end(), [](const auto& p) { return p->prepares_sample(); });
  model.simulation = std::make_unique<Simulation>(SimulationSettings{.particle_law = c.contact,
                                                                     .gravity = c.gravity,
                                                                     .local_damping = c.local_damping,
                                                                     .skin = c.skin,
                                                                     .threads = c.threads,
                                                                     .install_bonds_at_start = !prepared,
                                                                     .max_overlap_fraction = c.timestep.max_overlap_fraction,
                                                                     .material_laws = c.material_laws,
                                                                     .step_bound = c.timestep.step_bound});
  Simulation& sim = *model.simulation;

  // 2. Rigid walls and the pile.
  for (const auto& w : layout.walls) sim.add_wall(make_wall(w.name, w.mesh, WallMotion::prescribed, w.contact, w.velocity, w.start_step));
  if (c.pile) {
    // A pile that starts at equilibrium rests until DemBackend sets it moving (foundation_loading.hpp).
    Wall pile = make_wall("pile", make_pile_mesh(c.pile->geometry), WallMotion::prescribed, c.pile->contact,
                          c.pile->start_when ? Vec3{} : c.pile->velocity, c.pile->start_step);
    pile.facet_force.resize(pile.facet_count());  // its tip and shaft forces
    model.pile_wall = sim.add_wall(std::move(pile));
  }

  // 3. Particles; a generated sphere cut by a rigid wall would start with a huge overlap.
  if (c.particles.pcrm) {
    add_generated_body(model, c);
    return finish_model(model, c, layout, false);
  }
  for (std::size_t k = 0; k < layout.spheres.size(); ++k) {
    const GeneratedSphere& s = layout.spheres[k];
    bool cut = false;
    for (const auto& wall : sim.walls()) cut = cut || cut_by_wall(s.centre, s.radius, wall);
    cut = cut || (c.pile && inside_pile(s, c.pile->geometry));
    if (cut) {
      ++model.removed_particles;
      continue;
    }
    sim.add_sphere(std::int64_t(k), s.centre, s.radius, c.particles.density);
  }
  return finish_model(model, c, layout, prepared);
}

}  // namespace dfc::dem
