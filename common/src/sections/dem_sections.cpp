// The dem_server section, declared once (dem_sections.hpp). Sources: Itasca
// PFC3D (walls, local damping, the critical time step); Ciantia et al. 2015,
// doi 10.1680/geot.14.P.223 (periodic cell replication, "pcrm", and particle
// upscaling by S); the DEM docs (docs/dem_generation.md, docs/dem_periodic.md,
// docs/dem_ucs.md, docs/dem_triaxial_walls.md, docs/open_pile.md) say how
// each part is used.
#include "dfc/common/sections/dem_sections.hpp"

#include "dfc/common/config_reader.hpp"
#include "dfc/common/sections/dem_contact_laws.hpp"

namespace dfc::sections {

namespace {

using P = ParameterDeclaration;

constexpr Bounds kFraction{0.0, 1.0};
constexpr Bounds kOpenFraction{0.0, 1.0, true};  // (0, 1]

// Upscaling by S of the generators' lengths: radii (and an REV's edges) are
// multiplied by S, so that a run keeps its sphere count per REV with fewer,
// larger spheres over the same domain.
P times_s(P p) { return p.upscaled("multiplied by S", 1.0); }

P radius_min() { return times_s(P::number("radius_min_m", "m", "smallest sphere radius (uniform distribution)").positive()); }
P radius_max() { return times_s(P::number("radius_max_m", "m", "largest sphere radius, >= radius_min_m").positive()); }
P seed() { return P::integer("seed", "seed of the random numbers (same seed, same packing)").integer_within(0).fallback(1); }
P axis_xy() { return P::numbers("axis_xy_m", "m", "[x, y] of the vertical axis").fallback({0.0, 0.0}); }
P start_step() { return P::integer("start_step", "the step from which it moves").integer_within(0).fallback(0); }
P velocity() { return P::vector3("velocity_m_s", "m/s", "constant velocity").fallback({0.0, 0.0, 0.0}); }
P contact_of_walls() { return P::object("contact", dem_contact()).optional("wall_contact"); }
P min_corner() { return P::vector3("min_m", "m", "corner with the smallest coordinates"); }
P max_corner() { return P::vector3("max_m", "m", "corner with the largest coordinates, each > min_m's"); }
P axis() { return P::string("axis", "the loaded axis").one_of({"x", "y", "z"}).fallback("z"); }
P max_strain_rate() {
  return P::number("max_strain_rate_per_s", "1/s", "cap of the strain rate of a stress-controlled edge or wall pair").positive().optional("1e-4 / dt");
}

// --- regions ---------------------------------------------------------------

const SectionDeclaration& box_region_keys() {
  static const SectionDeclaration s{.name = "dem.region.box", .doc = "an axis-aligned box", .parameters = {min_corner(), max_corner()}};
  return s;
}

const SectionDeclaration& cylinder_region_keys() {
  static const SectionDeclaration s{
      .name = "dem.region.cylinder",
      .doc = "a vertical cylinder",
      .parameters = {P::number("radius_m", "m", "radius").positive(), P::number("z_min_m", "m", "height of the base"),
                     P::number("z_max_m", "m", "height of the top, > z_min_m"), axis_xy()},
  };
  return s;
}

const SectionDeclaration& region() {
  static const SectionDeclaration s{
      .name = "dem.region",
      .doc = "a region of space",
      .parameters = {P::string("type", "shape").one_of({"box", "cylinder"})},
      .selector = "type",
      .variants = {{"box", box_region_keys().doc, &box_region_keys()}, {"cylinder", cylinder_region_keys().doc, &cylinder_region_keys()}},
  };
  return s;
}

// --- stages run to equilibrium and the servo ------------------------------------

std::vector<P> equilibrium_target_keys() {
  return {P::number("tolerance", "-", "relative stress error at which the stage may end").within(kOpenFraction).fallback(kDefaultEquilibriumTolerance),
          P::number("unbalanced_force_ratio", "-", "unbalanced-force ratio at which the stage may end").within(kOpenFraction).fallback(kDefaultEquilibriumUnbalancedForceRatio),
          P::integer("max_steps", "most steps the stage may take (the run fails if the target is not met)").integer_within(1).fallback(kDefaultEquilibriumMaxSteps),
          P::integer("check_every", "steps between two checks of the target").integer_within(1).fallback(kDefaultEquilibriumCheckEvery)};
}

const SectionDeclaration& equilibrium_target() {
  static const SectionDeclaration s{.name = "dem.equilibrium_target",
                                    .doc = "a servo-controlled stage that runs until the stress error and the unbalanced force are small",
                                    .parameters = equilibrium_target_keys()};
  return s;
}

const SectionDeclaration& servo() {
  static const SectionDeclaration s{
      .name = "dem.servo",
      .doc = "the stress servo of cell edges or walls",
      .parameters = {P::number("gain", "-", "fraction of the stress error removed per step for an affine response").within(kOpenFraction).fallback(kDefaultServoGain),
                     max_strain_rate()},
  };
  return s;
}

// --- the periodic cell -----------------------------------------------------------

P cell_stress(const char* doc) { return P::number("stress_pa", "Pa", doc).positive(); }
P lateral_ratio() { return P::number("lateral_ratio", "-", "the two other edges are held at lateral_ratio x stress_pa").positive(); }

const SectionDeclaration& isotropic_keys() {
  static const SectionDeclaration s{.name = "dem.cell_loading.isotropic", .doc = "mean stress p on all three edges",
                                    .parameters = {cell_stress("p")}};
  return s;
}
const SectionDeclaration& k0_keys() {
  static const SectionDeclaration s{.name = "dem.cell_loading.k0", .doc = "sigma_v on the axis, the lateral edges fixed (one-dimensional compression)",
                                    .parameters = {cell_stress("sigma_v on the axis"), axis()}};
  return s;
}
const SectionDeclaration& anisotropic_keys() {
  static const SectionDeclaration s{.name = "dem.cell_loading.anisotropic", .doc = "sigma_v on the axis, lateral_ratio x sigma_v on the two others",
                                    .parameters = {cell_stress("sigma_v on the axis"), axis(), lateral_ratio()}};
  return s;
}
const SectionDeclaration& triaxial_cell_keys() {
  static const SectionDeclaration s{
      .name = "dem.cell_loading.triaxial",
      .doc = "a constant axial strain rate, the lateral edges held at sigma_3",
      .parameters = {P::number("stress_pa", "Pa", "sigma_3 (0: unconfined, the UCS of an REV)").at_least(0.0),
                     P::number("axial_strain_rate_per_s", "1/s",
                               "axial strain rate, not 0: > 0 compresses (triaxial compression, UCS), < 0 pulls (direct tension)"),
                     axis()},
  };
  return s;
}
const SectionDeclaration& strain_rate_keys() {
  static const SectionDeclaration s{.name = "dem.cell_loading.strain_rate", .doc = "each edge at a given strain rate",
                                    .parameters = {P::vector3("strain_rate_per_s", "1/s", "edge strain rates [x, y, z], extension positive")}};
  return s;
}

std::vector<SectionVariant> stress_modes() {
  return {{"isotropic", isotropic_keys().doc, &isotropic_keys()},
          {"k0", k0_keys().doc, &k0_keys()},
          {"anisotropic", anisotropic_keys().doc, &anisotropic_keys()}};
}

const SectionDeclaration& cell_consolidation() {
  static const SectionDeclaration s{
      .name = "dem.periodic.consolidation",
      .doc = "preparation before the coupled run, the servo to a stress state (bonds are installed after it)",
      .parameters =
          [] {
            std::vector<P> keys{P::string("mode", "stress state").one_of({"isotropic", "k0", "anisotropic"})};
            for (P& p : equilibrium_target_keys()) keys.push_back(std::move(p));
            return keys;
          }(),
      .selector = "mode",
      .variants = stress_modes(),
  };
  return s;
}

const SectionDeclaration& cell_loading() {
  static const SectionDeclaration s{
      .name = "dem.periodic.loading",
      .doc = "what the cell's edges do during advance",
      .parameters = {P::string("mode", "loading").one_of({"none", "isotropic", "k0", "anisotropic", "triaxial", "strain_rate"})},
      .selector = "mode",
      .variants =
          [] {
            std::vector<SectionVariant> modes{{"none", "the edges stay as they are", nullptr}};
            for (SectionVariant& v : stress_modes()) modes.push_back(std::move(v));
            modes.push_back({"triaxial", triaxial_cell_keys().doc, &triaxial_cell_keys()});
            modes.push_back({"strain_rate", strain_rate_keys().doc, &strain_rate_keys()});
            return modes;
          }(),
  };
  return s;
}

const SectionDeclaration& periodic() {
  static const SectionDeclaration s{
      .name = "dem.periodic",
      .doc = "a periodic (REV) cell (docs/dem_periodic.md); adds the monitors cell_stress_xx/yy/zz_pa (Love-Weber, compression positive), "
             "cell_strain_xx/yy/zz ((L0 - L)/L0) and porosity",
      .parameters = {P::vector3("min_m", "m", "lower corner of the cell"),
                     P::vector3("max_m", "m", "upper corner; each periodic edge at least 2 (2 r_max + skin)"),
                     P::string("axes", "the periodic axes, e.g. \"xy\" with a floor wall closing z").fallback("xyz"),
                     P::object("servo", servo()).optional("the servo's defaults"),
                     P::object("consolidation", cell_consolidation()).optional("no preparation"),
                     P::object("loading", cell_loading()).optional("the edges stay as they are")},
  };
  return s;
}

// --- particle generators -------------------------------------------------------------

std::vector<P> radius_expansion_keys() {
  return {radius_min(),
          radius_max(),
          P::number("porosity", "-", "target porosity in (0, 1), met exactly after the last stage").within(Bounds{0.0, 1.0, true}),
          P::number("multiplier", "-", "final / initial radius").within(Bounds{1.0, 10.0}).fallback(1.6),
          P::integer("stages", "growth stages").integer_within(1).fallback(10),
          P::integer("relax_steps", "steps after each stage").integer_within(0).fallback(1000),
          seed()};
}

const SectionDeclaration& lattice_keys() {
  static const SectionDeclaration s{
      .name = "dem.particles.lattice",
      .doc = "spheres on a lattice filling a region, radii uniform in [radius_min_m, radius_max_m]",
      .parameters = {radius_min(), radius_max(),
                     P::number("spacing_factor", "-", "lattice pitch / (2 radius_max_m)").within(Bounds{1.0, 10.0}).fallback(1.05),
                     P::string("arrangement", "cubic, or fcc (close-packed layers: a denser start that settles faster)")
                         .one_of({"cubic", "fcc"})
                         .fallback("cubic"),
                     seed(), P::object("region", region())},
  };
  return s;
}

const SectionDeclaration& list_keys() {
  static const SectionDeclaration s{
      .name = "dem.particles.list",
      .doc = "the spheres given one by one (taken as given: upscaling.scale_factor must be 1)",
      .parameters = {P::any("spheres", "[[x, y, z, radius], ...] in m, a non-empty array")},
  };
  return s;
}

const SectionDeclaration& radius_expansion_generator_keys() {
  static const SectionDeclaration s{
      .name = "dem.particles.radius_expansion",
      .doc = "spheres placed at random without overlap at radius/multiplier in the periodic cell (or the box of the triaxial walls), then grown "
             "in stages to the porosity (needs \"periodic\" or \"triaxial\")",
      .parameters = radius_expansion_keys(),
  };
  return s;
}

const SectionDeclaration& pcrm_rev() {
  static const SectionDeclaration s{
      .name = "dem.particles.pcrm.rev",
      .doc = "the REV: a radius expansion in a periodic cell, the servo to the installation stress, bonds, the servo to sigma_ref on z and K0 "
             "sigma_ref on x and y",
      .parameters =
          [] {
            std::vector<P> keys = radius_expansion_keys();
            keys.push_back(times_s(P::vector3("cell_m", "m", "edges of the cell [lx, ly, lz] at S = 1").positive()));
            keys.push_back(P::number("stress_pa", "Pa", "sigma_ref on z").positive().optional("sigma_v at the region's mid-depth"));
            keys.push_back(P::number("installation_stress_pa", "Pa",
                                     "isotropic stress at which the unbonded packing is consolidated and its bonds installed (Potyondy & Cundall "
                                     "2004, section 3.1): a property of the rock's genesis, independent of sigma_ref and the g-level")
                               .positive()
                               .fallback(kDefaultRevInstallationStress));
            keys.push_back(P::object("servo", servo()).optional("the servo's defaults"));
            keys.push_back(P::object("consolidation", equilibrium_target()).optional("the target's defaults (both servo stages)"));
            return keys;
          }(),
  };
  return s;
}

const SectionDeclaration& pcrm_stress() {
  static const SectionDeclaration s{
      .name = "dem.particles.pcrm.stress",
      .doc = "the stress the tiled REV is brought to: sigma_v(z) = rho_s (1 - n) |g| (surface_z_m - z) + surcharge_pa, sigma_h = K0 sigma_v",
      .parameters = {P::number("k0", "-", "sigma_h / sigma_v").positive(),
                     P::number("surface_z_m", "m", "height of the free surface").optional("the top of the region"),
                     P::number("surcharge_pa", "Pa", "vertical stress on the surface").at_least(0.0).fallback(0.0)},
  };
  return s;
}

const SectionDeclaration& pcrm_zone() {
  static const SectionDeclaration s{
      .name = "dem.particles.pcrm.zone",
      .doc = "a zone of graded upscaling: a sphere belongs to the first zone whose region holds its centre",
      .parameters = {P::number("scale_factor", "-", "upscaling factor S of the zone").positive(),
                     P::object("region", region()).optional("the rest of particles.region (last zone only)")},
  };
  return s;
}

const SectionDeclaration& pcrm_keys() {
  static const SectionDeclaration s{
      .name = "dem.particles.pcrm",
      .doc = "periodic cell replication at N g (docs/dem_generation.md): an REV prepared, tiled over the region with its contacts and bonds, "
             "trimmed, its bonds scaled to the geostatic stress; needs a law whose intact bond keeps its force (soft_bond, damage_bond)",
      .parameters = {P::object("rev", pcrm_rev()),
                     P::object("region", region()),
                     P::object("stress", pcrm_stress()),
                     P::number("protrusion_fraction", "-", "a sphere may stick out of the region by this fraction of its radius (0: whole spheres)")
                         .within(Bounds{0.0, 0.5})
                         .fallback(0.0),
                     P::objects("zones", pcrm_zone())
                         .optional("one zone, the section's upscaling.scale_factor; with zones the REV, walls and pile take the first zone's S, "
                                   "pairs of two zones mix the upscaled law parameters, particles carry the zone as \"material\""),
                     P::number("seam_overlap_fraction", "-",
                               "where zones meet, a sphere overlapping one of an earlier zone by more than this fraction of the smaller radius "
                               "is removed")
                         .within(Bounds{0.0, 0.5})
                         .fallback(0.1),
                     P::boolean("seat_on_walls", "move each outermost sphere whose path is free onto the floor and the coupling wall").fallback(true)},
  };
  return s;
}

const SectionDeclaration& particles() {
  static const SectionDeclaration s{
      .name = "dem.particles",
      .doc = "the spheres and how they are made",
      .parameters = {P::string("generator", "how the spheres are made").one_of({"lattice", "list", "radius_expansion", "pcrm"}),
                     P::number("density_kg_m3", "kg/m3", "particle density").positive()},
      .selector = "generator",
      .variants = {{"lattice", lattice_keys().doc, &lattice_keys()},
                   {"list", list_keys().doc, &list_keys()},
                   {"radius_expansion", radius_expansion_generator_keys().doc, &radius_expansion_generator_keys()},
                   {"pcrm", pcrm_keys().doc, &pcrm_keys()}},
  };
  return s;
}

// --- walls, pile, loadings ---------------------------------------------------------

const SectionDeclaration& plane_wall_keys() {
  static const SectionDeclaration s{
      .name = "dem.wall.plane",
      .doc = "a square plane wall",
      .parameters = {P::vector3("point_m", "m", "a point of the plane"), P::vector3("normal", "-", "normal towards the particles (not zero)"),
                     P::number("half_size_m", "m", "half the edge of the square").positive().optional("covers the particles' bounding box")},
  };
  return s;
}

const SectionDeclaration& facet_wall_keys() {
  static const SectionDeclaration s{
      .name = "dem.wall.facets",
      .doc = "a wall of triangles",
      .parameters = {P::any("vertices_m", "[[x, y, z], ...] in m, at least 3"), P::any("facets", "[[i, j, k], ...] indices into vertices_m")},
  };
  return s;
}

const SectionDeclaration& wall() {
  static const SectionDeclaration s{
      .name = "dem.wall",
      .doc = "a rigid wall; monitors wall_<name>_force_n and wall_<name>_moment_nm",
      .parameters = {P::string("type", "geometry").one_of({"plane", "facets"}),
                     P::string("name", "letters, digits and '_' (part of monitor names; \"pile\" and \"interface\" are reserved)")
                         .optional("wall<index>"),
                     velocity(), start_step(), contact_of_walls()},
      .selector = "type",
      .variants = {{"plane", plane_wall_keys().doc, &plane_wall_keys()}, {"facets", facet_wall_keys().doc, &facet_wall_keys()}},
  };
  return s;
}

const SectionDeclaration& pile_start_when() {
  static const SectionDeclaration s{
      .name = "dem.pile.start_when",
      .doc = "rest until, at or after start_step, the particles are in equilibrium: loading after equilibrium",
      .parameters = {P::number("unbalanced_force_ratio", "-", "the pile starts once the unbalanced-force ratio is at most this, e.g. 0.002")
                         .within(kOpenFraction)},
  };
  return s;
}

const SectionDeclaration& pile() {
  static const SectionDeclaration s{
      .name = "dem.pile",
      .doc = "a rigid pile: a closed cylinder with a flat tip, or an open-ended tube with wall_thickness_m (monitors pile_force_n, pile_tip_force_n, "
             "pile_shaft_force_n, pile_displacement_m, pile_inertial_number; a tube also pile_inner_shaft_force_n, pile_outer_shaft_force_n, pile_plug_length_m, "
             "pile_plug_particles)",
      .parameters = {axis_xy(), P::number("radius_m", "m", "outer radius").positive(), P::number("tip_z_m", "m", "height of the tip"),
                     P::number("length_m", "m", "length above the tip").positive(),
                     P::integer("sides", "sides of the prism the circle is drawn with (1000 is within 5e-6 of the circle)").integer_within(3, 1000).fallback(24),
                     P::number("wall_thickness_m", "m", "wall of an open-ended tube, < radius_m").positive().optional("a closed pile"),
                     velocity(), start_step(), P::object("start_when", pile_start_when()).optional("moves from start_step"),
                     P::integer("ramp_steps", "the velocity rises linearly from 0 over this many steps").integer_within(0).fallback(0),
                     P::number("local_damping", "-", "local damping alpha from the pile's first moving step, < 1")
                         .within(kFraction)
                         .optional("damping.local throughout"),
                     contact_of_walls()},
  };
  return s;
}

const SectionDeclaration& ucs() {
  static const SectionDeclaration s{
      .name = "dem.ucs",
      .doc = "unconfined compression between two platen walls (docs/dem_ucs.md); monitors axial_stress_pa (compression positive, averaged over "
             "the advance and both platens) and axial_strain ((H0 - H)/H0)",
      .parameters = {P::string("top_wall", "name of the top platen wall"), P::string("bottom_wall", "name of the bottom platen wall"),
                     P::number("area_m2", "m2", "sample cross-section")
                         .positive()
                         .optional("derived from a lattice bed with platens normal to z (disc or x-y box through the outermost particles)"),
                     start_step(), P::boolean("seat_platens", "move both platens along the axis onto the outermost particles").fallback(true),
                     P::number("strain_rate_per_s", "1/s", "moves each platen at H0/2 x this towards the other (the platens then have no velocity_m_s)")
                         .positive()
                         .optional("the platens' own velocity_m_s")},
  };
  return s;
}

const SectionDeclaration& triaxial() {
  static const SectionDeclaration s{
      .name = "dem.triaxial",
      .doc = "triaxial compression in six rigid plane walls (docs/dem_triaxial_walls.md): all six servo-controlled to sigma_3, bonds, then the "
             "platens close while the lateral walls hold sigma_3; monitors axial_stress_pa, lateral_stress_pa, deviatoric_stress_pa, "
             "axial_strain, volumetric_strain, porosity",
      .parameters = {P::string("top_wall", "name of the top platen wall"), P::string("bottom_wall", "name of the bottom platen wall"),
                     P::strings("lateral_walls", "four wall names: the two of one opposite pair, then the two of the other"),
                     P::number("confining_stress_pa", "Pa", "sigma_3").positive(),
                     P::number("strain_rate_per_s", "1/s", "axial strain rate (each platen moves at H0/2 x this)").positive(),
                     P::boolean("seat_walls", "move every wall onto the outermost particles").fallback(true),
                     P::object("servo", servo()).optional("the servo's defaults"),
                     P::object("confinement", equilibrium_target()).optional("the target's defaults")},
  };
  return s;
}

// --- small sections of the root -------------------------------------------------------

const SectionDeclaration& upscaling() {
  static const SectionDeclaration s{
      .name = "dem.upscaling",
      .doc = "particle upscaling: every generated radius multiplied by S, every contact-law parameter by its law's rule (S^exponent); the "
             "domain, walls and strain rates stay",
      .parameters = {P::number("scale_factor", "-", "S").positive()},
  };
  return s;
}

const SectionDeclaration& damping() {
  static const SectionDeclaration s{
      .name = "dem.damping",
      .doc = "numerical damping",
      .parameters = {P::number("local", "-", "local non-viscous damping alpha, < 1 (1 would cancel every driving force)")
                         .within(kFraction)
                         .fallback(kDefaultLocalDamping)},
  };
  return s;
}

const SectionDeclaration& timestep() {
  static const SectionDeclaration s{
      .name = "dem.timestep",
      .doc = "the time step: a fraction of the critical step, or a fixed dt_s (refused above the critical step)",
      .parameters = {P::number("dt_s", "s", "fixed time step").positive().optional("fraction_of_critical x the critical step"),
                     P::number("fraction_of_critical", "-", "fraction of the critical time step").within(kOpenFraction).fallback(kDefaultFractionOfCritical),
                     // The instability guard: a run whose step is too large or whose walls
                     // move too fast sees overlaps grow without bound, while a loaded contact
                     // sits at F/k_n (a few per cent of the radius for most of a body). Where
                     // a graded body puts a small sphere between a pile and a sphere several
                     // times larger, that soft contact can carry its load at more than half
                     // the small radius; such a model raises the limit.
                     P::number("max_overlap_fraction", "-",
                               "the run stops as unstable when a contact overlap exceeds this fraction of the smaller radius (a wall contact: of the particle's)")
                         .within(kOpenFraction)
                         .fallback(kDefaultMaxOverlapFraction),
                     // dem_server/include/dfc/dem/timestep.hpp: a sphere's contacts are bounded
                     // by the law's stiffness at its own radius whatever its partners' sizes;
                     // the body's largest radius (the bound before 2026-12) is
                     // sqrt(r_max / r_min) more cautious on a graded body.
                     P::string("stiffness_bound", "which radius each sphere's contact stiffness bound is taken at in the critical step: its own "
                                                  "(per_particle), or the body's largest (largest_radius: sqrt(r_max/r_min) smaller steps on a graded body)")
                         .one_of({"per_particle", "largest_radius"})
                         .fallback("per_particle")},
  };
  return s;
}

const SectionDeclaration& neighbour() {
  static const SectionDeclaration s{
      .name = "dem.neighbour",
      .doc = "the Verlet neighbour list",
      .parameters = {P::number("skin_m", "m", "Verlet skin").positive().optional("0.2 x the largest radius")},
  };
  return s;
}

const SectionDeclaration& snapshot() {
  static const SectionDeclaration s{
      .name = "dem.snapshot",
      .doc = "what each snapshot of the particles holds beyond their position, radius, velocity and id (docs/looking_at_a_run.md)",
      // The default is the output before the key existed; contacts are
      // opt-in because at 4-6 per sphere they double a snapshot's size.
      .parameters = {P::strings("contents", "the optional arrays: particle_stress (Love-Weber stress per sphere), bonds (every bonded pair as a "
                                            "line), contacts (every pair carrying a force as a line), walls (walls and pile as triangles)")
                         .one_of({"particle_stress", "bonds", "contacts", "walls"})
                         .fallback(nlohmann::json::array({"particle_stress", "bonds", "walls"})),
                     P::number("contacts_min_force_n", "N", "contacts whose normal force is smaller in magnitude are left out of the snapshot")
                         .at_least(0.0)
                         .fallback(0.0)},
  };
  return s;
}

}  // namespace

const SectionDeclaration& dem_server() {
  static const SectionDeclaration s{
      .name = "dem_server",
      .doc = "bonded discrete elements (PFC3D-style soft spheres, velocity Verlet, local damping); SI units",
      .parameters = {P::object("particles", particles()),
                     P::object("upscaling", upscaling()).optional("S = 1"),
                     P::object("contact", dem_contact()),
                     P::object("wall_contact", dem_contact()).optional("contact (used by walls, the pile and the coupling wall)"),
                     P::object("damping", damping()).optional("the damping section's defaults"),
                     P::object("timestep", timestep()).optional("the timestep section's defaults"),
                     P::vector3("gravity_m_s2", "m/s2", "total acceleration (the coupler passes N g here)").fallback({0.0, 0.0, 0.0}),
                     P::object("neighbour", neighbour()).optional("the neighbour section's defaults"),
                     P::object("periodic", periodic()).optional("no periodic cell"),
                     P::objects("walls", wall()).optional("no walls"),
                     P::object("pile", pile()).optional("no pile"),
                     P::object("ucs", ucs()).optional("no UCS loading"),
                     P::object("triaxial", triaxial()).optional("no triaxial loading"),
                     P::object("snapshot", snapshot()).optional("the snapshot section's defaults"),
                     thread_count_declaration()},
  };
  return s;
}

}  // namespace dfc::sections
