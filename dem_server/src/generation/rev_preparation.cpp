#include "dfc/dem/rev_preparation.hpp"

#include <algorithm>
#include <cmath>

#include "dfc/common/errors.hpp"
#include "dfc/dem/cell_stress.hpp"
#include "dfc/dem/sample_preparation.hpp"
#include "dfc/dem/timestep.hpp"

namespace dfc::dem {

namespace {

/// s, critical step of the packing once every sphere has its final radius.
double grown_critical_step(const Simulation& sim, const std::vector<double>& final_radius) {
  ParticleStore grown = sim.particles();
  for (std::size_t i = 0; i < grown.size(); ++i) grown.set_radius(i, final_radius[std::size_t(grown.id[i])]);
  const ContactLawSetting& law = sim.settings().particle_law;
  return critical_timestep(grown, [&](double radius) { return law.stiffness_bound(radius); }, sim.settings().step_bound);
}

/// Stops every particle. Used before the bonds are installed: an intact bond's
/// force is its stored history alone, so installing them removes every
/// contact force of the consolidated packing, which is then in equilibrium at
/// zero stress, and only the servo's leftover motion (the stage stops at an
/// unbalanced-force ratio of a few per cent) would still load the new bonds.
/// Measured on the chalk REV consolidated at 100 kPa: that motion yielded 5
/// or 6 bonds and left about 30 Pa in the cell whatever sigma_ref, 13 % of the
/// reference stress of the small model at 1 g, copied unscaled into the body
/// (stress_scaling.hpp scales intact bonds only). At rest they are installed
/// unloaded, as the law's rule and Potyondy & Cundall (2004, §3.1: bonds on
/// a packing in static equilibrium) mean, and nothing is locked in.
void bring_to_rest(Simulation& sim) {
  ParticleStore& p = sim.particles_for_edit();
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.velocity[i] = {};
    p.angular_velocity[i] = {};
  }
}

/// The pairs with a history, their images across the cell faces, and the rows.
void collect_pairs(const Simulation& sim, PreparedRev& rev) {
  const PairContacts& pairs = sim.pair_contacts();
  const ParticleStore& p = sim.particles();
  const PeriodicSpace space(rev.cell);
  const Vec3 l = rev.cell.length();
  rev.stride = pairs.whole_stride();
  std::vector<double> row(rev.stride);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (pairs.whole_row_is_zero(k)) continue;
    pairs.copy_whole_row(k, row.data());
    const std::uint32_t i = pairs.first[k], j = pairs.second[k];
    const Vec3 xi = rev.cell.wrap(p.position[i]), xj = rev.cell.wrap(p.position[j]);
    const Vec3 shift = xi + space.branch(xi, xj) - xj;  // whole cell lengths
    rev.pairs.push_back({std::uint32_t(p.id[i]), std::uint32_t(p.id[j]),
                         {int(std::lround(shift.x / l.x)), int(std::lround(shift.y / l.y)), int(std::lround(shift.z / l.z))}});
    rev.rows.insert(rev.rows.end(), row.begin(), row.end());
  }
}

}  // namespace

PreparedRev prepare_rev(const RevSpec& spec, SimulationSettings settings, const std::string& key) {
  settings.gravity = {};
  settings.install_bonds_at_start = false;
  Simulation sim(std::move(settings));
  // Placement and the cell's width are checked here, where the keys are known:
  // every edge must hold 2 (2 r_max + reach) with the final radii (the
  // simulation's own check would only fire during the expansion, keyless).
  const double r_max = spec.particles.radius_max;
  const double reach = std::max(sim.settings().skin > 0.0 ? sim.settings().skin : 0.2 * r_max, sim.settings().particle_law.bond_gap());
  const Vec3 edge = spec.cell.length();
  if (std::min({edge.x, edge.y, edge.z}) < 2.0 * (2.0 * r_max + reach))
    throw ConfigError(key + ".cell_m", "the REV cell must be at least 2 (2 r_max + skin or bond gap) = " + std::to_string(2.0 * (2.0 * r_max + reach)) +
                                           " m long on every axis (after upscaling by S); it is " + std::to_string(std::min({edge.x, edge.y, edge.z})) +
                                           " m: widen cell_m");
  ExpansionPacking packing;
  try {
    packing = place_for_radius_expansion(spec.particles, spec.cell);
  } catch (const UserError& e) {
    throw ConfigError(key + ".multiplier", e.what());
  }
  for (std::size_t k = 0; k < packing.spheres.size(); ++k)
    sim.add_sphere(std::int64_t(k), packing.spheres[k].centre, packing.spheres[k].radius, spec.density);
  try {
    sim.set_periodic_cell(spec.cell);
  } catch (const UserError& e) {
    throw ConfigError(key + ".cell_m", e.what());
  }

  PreparedRev rev;
  rev.dt = spec.fraction_of_critical * grown_critical_step(sim, packing.final_radius);
  const double max_rate = spec.max_strain_rate.value_or(1e-4 / rev.dt);
  const std::string servo_key = key + ".servo";
  // 1-2: unbonded, PFC's order (Potyondy & Cundall 2004 §3.1), isotropic at
  // the installation stress sigma_0, whatever sigma_ref (rev_preparation.hpp):
  // a loose frictional packing held at a deviatoric K0 state creeps and never
  // settles to the servo's tolerance.
  const ExpansionReport expansion = expand_radii(sim, packing.final_radius, spec.particles, spec.fraction_of_critical, spec.cell.volume());
  ConsolidationSpec isotropic = spec.consolidation;
  const CellLoading& target = spec.consolidation.loading;
  isotropic.loading = {.mode = CellLoading::Mode::isotropic, .axis = target.axis,
                       .stress = spec.installation_stress, .lateral_ratio = 1.0, .axial_rate = 0.0, .strain_rate = {}};
  const Consolidation unbonded = consolidate(sim, isotropic, spec.servo_gain, max_rate, rev.dt, key + ".consolidation", servo_key);
  // 3-4: bonded at rest, then loaded to sigma_ref: the bonds carry it all,
  // elastically, so the REV's state is proportional to sigma_ref.
  bring_to_rest(sim);
  install_bonds(sim, rev.dt);
  const Consolidation bonded =
      consolidate(sim, spec.consolidation, spec.servo_gain, max_rate, rev.dt, key + ".consolidation (bonded stage)", servo_key);
  sim.step(rev.dt);  // complete contact outputs at the final cell

  rev.cell = *sim.periodic_cell();
  rev.cell.strain_rate = {};
  const ParticleStore& p = sim.particles();
  rev.spheres.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) rev.spheres[std::size_t(p.id[i])] = {rev.cell.wrap(p.position[i]), p.radius[i]};
  collect_pairs(sim, rev);
  rev.stress = measure_cell_stress(sim).diagonal();
  rev.porosity = cell_porosity(p, rev.cell);
  rev.bonds = sim.bond_counts().intact;
  rev.damaged_bonds = sim.bond_counts().damaged;
  rev.steps = expansion.steps + unbonded.steps + bonded.steps + 2;
  return rev;
}

}  // namespace dfc::dem
