#include "dfc/dem/pcrm_generation.hpp"

#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

#include "dfc/common/errors.hpp"
#include "dfc/dem/boundary_seating.hpp"

namespace dfc::dem {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double region_mid_z(const BedRegion& r) {
  return r.shape == BedRegion::Shape::box ? 0.5 * (r.min.z + r.max.z) : 0.5 * (r.z_min + r.z_max);
}

}  // namespace

GeneratedBody generate_pcrm(const PcrmConfig& config, const SimulationSettings& settings, const Vec3& gravity) {
  if (!settings.particle_law.intact_force_from_history())
    throw ConfigError("contact.law", "generator \"pcrm\" scales the load of the REV's bonds to the self-weight field, which needs a law whose intact "
                                     "bond keeps its whole force in history: use \"soft_bond\" or \"damage_bond\" (\"" +
                                         settings.particle_law.info->keyword + "\" has an overlap term)");
  if (gravity.x != 0.0 || gravity.y != 0.0 || gravity.z > 0.0)
    throw ConfigError("gravity_m_s2", "generator \"pcrm\" measures depth down from particles.stress.surface_z_m, so gravity must point along -z");
  const double g = std::abs(gravity.z);
  if (g == 0.0 && config.profile.surcharge == 0.0)
    throw ConfigError("particles.stress.surcharge_pa", "without gravity the only stress is the surcharge: give gravity (the coupler's g_level) or a surcharge_pa > 0");

  GeneratedBody out;
  // Reference sigma_v: at mid-depth for the target porosity unless given.
  StressProfile nominal = config.profile;
  nominal.unit_weight = config.rev.density * (1.0 - config.rev.particles.porosity) * g;
  out.reference_stress = config.reference_stress.value_or(nominal.vertical(region_mid_z(config.region)));
  RevSpec rev_spec = config.rev;
  CellLoading& loading = rev_spec.consolidation.loading;
  loading.mode = CellLoading::Mode::anisotropic;
  loading.axis = 2;
  loading.stress = out.reference_stress;
  loading.lateral_ratio = config.profile.k0;

  const auto t0 = std::chrono::steady_clock::now();
  out.rev = prepare_rev(rev_spec, settings, "particles.rev");
  out.rev_seconds = seconds_since(t0);
  std::cerr << "dem_server: pcrm REV: " << out.rev.spheres.size() << " spheres, " << out.rev.bonds << " bonds (and " << out.rev.damaged_bonds << " damaged), porosity " << out.rev.porosity
            << ", stress [" << out.rev.stress.x << ", " << out.rev.stress.y << ", " << out.rev.stress.z << "] Pa, " << out.rev.steps << " steps, "
            << out.rev_seconds << " s" << std::endl;

  const auto t1 = std::chrono::steady_clock::now();
  if (config.zones.empty()) {
    out.body = replicate(out.rev, config.region, config.protrusion_fraction);
    out.zone_spheres = {out.body.spheres.size()};
  } else {
    ZonedBody zoned = replicate_zones(out.rev, settings.particle_law.info->history, config.region, config.zones, config.protrusion_fraction,
                                      config.seam_overlap_fraction);
    out.body = std::move(zoned.body);
    out.zone_spheres = std::move(zoned.zone_spheres);
    out.seam_removed = zoned.seam_removed;
    out.seam_seated = zoned.seam_seated;
    std::cerr << "dem_server: pcrm zones:";
    for (std::size_t k = 0; k < config.zones.size(); ++k) std::cerr << " S = " << config.zones[k].scale_factor << ": " << out.zone_spheres[k] << " spheres;";
    std::cerr << " at the seams " << out.seam_removed << " removed, " << out.seam_seated << " seated" << std::endl;
  }
  out.profile = config.profile;
  out.profile.unit_weight = config.rev.density * (1.0 - out.rev.porosity) * g;
  out.reference_stress = out.rev.stress.z;
  out.scaling = scale_to_profile(out.body, settings.particle_law.info->history, out.profile, out.reference_stress);
  out.replication_seconds = seconds_since(t1);
  std::cerr << "dem_server: pcrm replication: " << out.body.copies[0] << " x " << out.body.copies[1] << " x " << out.body.copies[2] << " copies, "
            << out.body.spheres.size() << " spheres, " << out.scaling.scaled_bonds << " bonds scaled by " << out.scaling.lambda_min << " to "
            << out.scaling.lambda_max << ", " << out.replication_seconds << " s" << std::endl;
  out.rev.rows.clear();
  out.rev.rows.shrink_to_fit();
  return out;
}

std::size_t fit_to_wall(Simulation& sim, const Wall& wall, const PcrmConfig& config, GeneratedBody& body) {
  const ParticleStore& p = sim.particles();
  const double fraction = std::max(config.protrusion_fraction, wall_contact_overlap_fraction);
  const std::size_t removed = sim.remove_particles_before_start([&](std::size_t i) { return cut_by_wall(p.position[i], p.radius[i], wall, fraction); });
  if (config.seat) body.seated += seat_on_wall(sim, wall, body.profile, face_areas(config.region)).seated;
  return removed;
}

}  // namespace dfc::dem
