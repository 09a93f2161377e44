#include "dfc/dem/particle_materials.hpp"
#include "dfc/dem/pcrm_generation.hpp"
#include "dfc/dem/periodic_config.hpp"
#include "dfc/dem/region_config.hpp"

namespace dfc::dem {


namespace {

std::vector<PcrmZone> read_zones(ConfigReader& particles) {
  std::vector<PcrmZone> zones;
  if (!particles.has("zones")) {
    particles.accept("zones");
    return zones;  // one zone: the section's upscaling.scale_factor
  }
  auto list = particles.children("zones");
  if (list.empty()) particles.fail("zones", "expected at least one zone {\"scale_factor\": S, \"region\": {...}}");
  if (list.size() > ParticleMaterials::max_count) particles.fail("zones", "at most " + std::to_string(ParticleMaterials::max_count) + " zones");
  for (std::size_t k = 0; k < list.size(); ++k) {
    PcrmZone zone;
    zone.scale_factor = list[k].number("scale_factor");
    if (auto region = list[k].optional_child("region")) zone.region = read_region(std::move(*region));
    else if (k + 1 < list.size()) list[k].fail("region", "every zone but the last needs a region (the last one takes the rest of particles.region)");
    list[k].finish();
    zones.push_back(zone);
  }
  return zones;
}

}  // namespace

PcrmConfig read_pcrm(ConfigReader& particles, double scale_factor, double density) {
  PcrmConfig c;
  c.zones = read_zones(particles);
  if (!c.zones.empty()) {
    if (scale_factor != 1.0)
      particles.fail("zones", "each zone gives its own scale_factor, and the REV, the walls and the pile take the first zone's: remove the section's "
                              "\"upscaling\"");
    scale_factor = c.zones.front().scale_factor;
  }
  c.scale_factor = scale_factor;
  c.seam_overlap_fraction = particles.number("seam_overlap_fraction");
  {
    ConfigReader rev = particles.child("rev");
    c.rev.particles = read_radius_expansion(rev);
    c.rev.particles.radius_min *= scale_factor;
    c.rev.particles.radius_max *= scale_factor;
    const auto edge = rev.vec3("cell_m");  // declared positive
    c.rev.cell.lo = {};
    c.rev.cell.hi = {scale_factor * edge[0], scale_factor * edge[1], scale_factor * edge[2]};
    c.rev.cell.periodic = {true, true, true};
    if (rev.has("stress_pa")) c.reference_stress = rev.number("stress_pa");
    else rev.accept("stress_pa");
    c.rev.installation_stress = rev.number("installation_stress_pa");
    PeriodicConfig servo;
    if (auto s = rev.optional_child("servo")) read_servo(std::move(*s), servo);
    c.rev.servo_gain = servo.servo_gain;
    c.rev.max_strain_rate = servo.max_strain_rate;
    if (auto cons = rev.optional_child("consolidation")) {
      static_cast<EquilibriumTarget&>(c.rev.consolidation) = read_equilibrium_target(*cons);
      cons->finish();
    }
    rev.finish();
  }
  c.rev.density = density;
  c.region = read_region(particles.child("region"));
  {
    ConfigReader stress = particles.child("stress");
    c.profile.k0 = stress.number("k0");
    if (stress.has("surface_z_m")) {
      c.profile.surface_z = stress.number("surface_z_m");
    } else {  // the top of the region
      stress.accept("surface_z_m");
      c.profile.surface_z = c.region.shape == BedRegion::Shape::box ? c.region.max.z : c.region.z_max;
    }
    c.profile.surcharge = stress.number("surcharge_pa");
    stress.finish();
  }
  c.protrusion_fraction = particles.number("protrusion_fraction");
  c.seat = particles.boolean("seat_on_walls");
  return c;
}

}  // namespace dfc::dem
