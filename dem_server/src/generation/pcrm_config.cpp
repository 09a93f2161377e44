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
    return zones;
  }
  auto list = particles.children("zones");
  if (list.empty()) particles.fail("zones", "expected at least one zone {\"scale_factor\": S, \"region\": {...}}");
  if (list.size() > ParticleMaterials::max_count) particles.fail("zones", "at most " + std::to_string(ParticleMaterials::max_count) + " zones");
  for (std::size_t k = 0; k < list.size(); ++k) {
    PcrmZone zone;
    zone.scale_factor = list[k].positive("scale_factor");
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
  c.seam_overlap_fraction = particles.number("seam_overlap_fraction", 0.1, Bounds{0.0, 0.5});
  {
    ConfigReader rev = particles.child("rev");
    c.rev.particles = read_radius_expansion(rev);
    c.rev.particles.radius_min *= scale_factor;
    c.rev.particles.radius_max *= scale_factor;
    const auto edge = rev.vec3("cell_m");
    if (!(edge[0] > 0.0 && edge[1] > 0.0 && edge[2] > 0.0)) rev.fail("cell_m", "expected three positive edge lengths [lx, ly, lz] in m");
    c.rev.cell.lo = {};
    c.rev.cell.hi = {scale_factor * edge[0], scale_factor * edge[1], scale_factor * edge[2]};
    c.rev.cell.periodic = {true, true, true};
    if (rev.has("stress_pa")) c.reference_stress = rev.positive("stress_pa");
    else rev.accept("stress_pa");
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
    c.profile.k0 = stress.positive("k0");
    c.profile.surface_z = stress.number("surface_z_m", c.region.shape == BedRegion::Shape::box ? c.region.max.z : c.region.z_max);
    c.profile.surcharge = stress.number("surcharge_pa", 0.0, Bounds{0.0});
    stress.finish();
  }
  c.protrusion_fraction = particles.number("protrusion_fraction", 0.0, Bounds{0.0, 0.5});
  c.seat = particles.boolean("seat_on_walls", true);
  return c;
}

std::string pcrm_help() {
  return R"(    pcrm (docs/dem_generation.md): periodic cell replication at N g. An REV is prepared (radius expansion,
             servo to sigma_ref on z and K0 sigma_ref on x, y, bonds, the servo again with the bonds), tiled over
             "region" with its contacts and bonds (across the cell faces too), trimmed to the region and its
             bonds scaled to sigma_v(z) = rho_s (1 - n) |g| (surface_z_m - z) + surcharge_pa, sigma_h = K0 sigma_v.
             rev (required): radius_min_m, radius_max_m, porosity, multiplier, stages, relax_steps, seed (as
                   radius_expansion), "cell_m":[lx, ly, lz] (required; at S = 1: upscaling multiplies radii and
                   cell by S, so the REV keeps its sphere count), "stress_pa" (sigma_ref on z; default sigma_v at
                   the region's mid-depth), "servo":{"gain":0.5, "max_strain_rate_per_s"},
                   "consolidation":{"tolerance":0.01, "unbalanced_force_ratio":0.01, "max_steps":200000,
                   "check_every":100} (both servo stages)
             region (required): {"type":"cylinder", "radius_m", "z_min_m", "z_max_m", "axis_xy_m":[0,0]} or
                   {"type":"box", "min_m", "max_m"}
             stress (required): {"k0" (sigma_h / sigma_v), "surface_z_m" (default: top of the region),
                   "surcharge_pa":0}
             protrusion_fraction (0, at most 0.5): a sphere may stick out of the region (and later out of the
                   coupling wall) by this fraction of its radius; 0 keeps whole spheres only
             zones: graded upscaling (docs/dem_generation.md §7), e.g. [{"scale_factor":2.1, "region":{cylinder r 4.8 mm}},
                   {"scale_factor":4.8}]: a sphere belongs to the first zone whose region holds its centre; the last
                   zone may omit its region (the rest). The REV is prepared at the first zone's S and scaled to each
                   zone's; the law's parameters are upscaled per zone, pairs of two zones mix them (geometric mean of
                   the parameters that scale with S, arithmetic of the others) and are bonded at the first step
                   (zero load, within the mixed bond gap). The walls and the pile use the first zone's S; the section's
                   "upscaling" must be absent. Particles carry the zone index as "material" in the snapshots.
             seam_overlap_fraction (0.1, at most 0.5): where two zones meet, a sphere overlapping one of an earlier
                   zone by more than this fraction of the smaller radius is removed
             seat_on_walls (true): move each outermost sphere whose path is free onto the bottom and lateral faces
                   (the floor and the coupling wall), with the overlap of its share of the face's stress
             needs a law whose intact bond keeps its force in history ("soft_bond" or "damage_bond")
)";
}

}  // namespace dfc::dem
