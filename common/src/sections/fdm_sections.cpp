// The fdm_server section, declared once (fdm_sections.hpp). Sources of the
// models' parameters: Itasca FLAC3D constitutive models (elastic,
// Mohr-Coulomb); Ciantia et al. 2024 (structured Cam Clay, doi
// 10.1016/j.compgeo.2023.106010) and docs/fdm_models.md.
#include "dfc/common/sections/fdm_sections.hpp"

#include "dfc/common/config_reader.hpp"

namespace dfc::sections {

namespace {

using P = ParameterDeclaration;

// Keys two mesh types share: one declaration each, listed in both variants.
P inner_radius() { return P::number("inner_radius_m", "m", "radius of the cavity").positive(); }
P outer_radius() { return P::number("outer_radius_m", "m", "outer radius of the mesh, > inner_radius_m").positive(); }
P zones_radial() { return P::integer("zones_radial", "zones from the cavity to the outer radius").integer_within(1).fallback(1); }
P grading_ratio() { return
    P::number("grading_ratio", "-", "radial spacing growth dr[k+1]/dr[k] counted outwards (> 1: finer at the cavity)").positive().fallback(1.0); }
P max_aspect_ratio() { return P::number("max_aspect_ratio", "-", "largest longest/shortest zone edge the mesh may have")
                               .at_least(1.0)
                               .fallback(kDefaultMaxAspectRatio); }

const SectionDeclaration& box_keys() {
  static const SectionDeclaration s{
      .name = "fdm.mesh.box",
      .doc = "a box meshed in hexahedral zones; face groups xmin xmax ymin ymax zmin zmax",
      .parameters = {P::vector3("origin_m", "m", "corner with the smallest coordinates").fallback({0.0, 0.0, 0.0}),
                     P::vector3("size_m", "m", "edge lengths [Lx, Ly, Lz]").positive(),
                     P::integers3("zones", "zones along x, y, z").integer_within(1),
                     P::vector3("grading", "-", "spacing growth per zone along +x, +y, +z").positive().fallback({1.0, 1.0, 1.0})},
  };
  return s;
}

const SectionDeclaration& cylinder_cavity_keys() {
  static const SectionDeclaration s{
      .name = "fdm.mesh.cylinder_cavity",
      .doc = "a thick cylinder about z around a cavity; face groups inner outer bottom top (theta_min theta_max for a sector; "
             "cavity_side cavity_floor with a floor)",
      .parameters = {inner_radius(), outer_radius(), P::number("z_bottom_m", "m", "height of the base").fallback(0.0),
                     P::number("height_m", "m", "height of the cylinder").positive(), zones_radial(),
                     P::integer("zones_around", "zones around the axis (>= 3 for the full circle)").integer_within(1).fallback(1),
                     P::integer("zones_vertical", "zones along z").integer_within(1).fallback(1), grading_ratio(),
                     P::number("angle_deg", "deg", "the sector 0..angle_deg").within(Bounds{0.0, 360.0, true}).fallback(360.0),
                     max_aspect_ratio(),
                     P::number("cavity_floor_z_m", "m",
                               "the cavity ends at this height on a zone level, a solid base below it (needs angle_deg 360 and zones_around "
                               "a multiple of 4)")
                         .optional("z_bottom_m: the cavity runs through the whole height")},
  };
  return s;
}

const SectionDeclaration& sphere_cavity_octant_keys() {
  static const SectionDeclaration s{
      .name = "fdm.mesh.sphere_cavity_octant",
      .doc = "the octant x, y, z >= 0 of a spherical shell; face groups inner outer xmin ymin zmin",
      .parameters = {inner_radius(), outer_radius(), zones_radial(),
                     P::integer("zones_around", "zones per patch edge (3 patches)").integer_within(1).fallback(1), grading_ratio(),
                     max_aspect_ratio()},
  };
  return s;
}

// Elasticity every model reads: E and nu, or K and G (either pair, not both).
const std::vector<P>& elastic_parameters() {
  static const std::vector<P> keys = {
      P::number("young_modulus_pa", "Pa", "Young's modulus E; give it with poisson_ratio").positive().optional("bulk_modulus_pa and shear_modulus_pa"),
      P::number("poisson_ratio", "-", "Poisson's ratio nu, < 0.5; give it with young_modulus_pa")
          .within(Bounds{-1.0, 0.5, true})
          .optional("bulk_modulus_pa and shear_modulus_pa"),
      P::number("bulk_modulus_pa", "Pa", "bulk modulus K; alternative to E and nu, give it with shear_modulus_pa").positive().optional("E and nu"),
      P::number("shear_modulus_pa", "Pa", "shear modulus G; give it with bulk_modulus_pa").positive().optional("E and nu"),
  };
  return keys;
}

std::vector<P> with_elastic(std::vector<P> own) {
  std::vector<P> keys = elastic_parameters();
  keys.insert(keys.end(), own.begin(), own.end());
  return keys;
}

const SectionDeclaration& elastic_keys() {
  static const SectionDeclaration s{.name = "fdm.material.elastic", .doc = "isotropic linear elasticity", .parameters = elastic_parameters()};
  return s;
}

const SectionDeclaration& mohr_coulomb_keys() {
  static const SectionDeclaration s{
      .name = "fdm.material.mohr_coulomb",
      .doc = "Mohr-Coulomb shear yield, non-associated flow, tension cut-off, perfectly plastic (FLAC3D form)",
      .parameters = with_elastic({
          P::number("cohesion_pa", "Pa", "cohesion c").at_least(0.0),
          P::number("friction_angle_deg", "deg", "friction angle phi, < 90").within(Bounds{0.0, 90.0}),
          P::number("dilation_angle_deg", "deg", "dilation angle psi <= phi (0: no plastic volume change)").at_least(0.0).fallback(0.0),
          P::number("tensile_strength_pa", "Pa", "tension cut-off sigma_t, capped at the apex c/tan(phi)").at_least(0.0),
      }),
  };
  return s;
}

const SectionDeclaration& structured_cam_clay_keys() {
  static const SectionDeclaration s{
      .name = "fdm.material.structured_cam_clay",
      .doc = "bonded Modified Cam Clay (Ciantia et al. 2024): p_s, p_t, M_f yield, M_g potential, hardening and debonding",
      .parameters = with_elastic({
          P::number("ps0_pa", "Pa", "initial p_s, preconsolidation of the unbonded material (raised to the initial stress if that lies outside)")
              .positive(),
          P::number("pt0_pa", "Pa", "initial p_t, bonding (isotropic tensile strength)").at_least(0.0),
          P::number("mf", "-", "M_f, slope controlling the yield-surface shape").positive(),
          P::number("mg", "-", "M_g, slope of the plastic potential").positive().optional("mf (associated flow)"),
          P::number("rho_s", "-", "rate of p_s hardening: dp_s = rho_s p_s (d eps_v^p + xi_s d eps_q^p)").fallback(0.0),
          P::number("rho_t", "-", "rate of debonding: dp_t = -rho_t p_t (|d eps_v^p| + xi_t d eps_q^p)").fallback(0.0),
          P::number("xi_s", "-", "weight of deviatoric plastic strain in the p_s law").fallback(0.0),
          P::number("xi_t", "-", "weight of deviatoric plastic strain in the p_t law").fallback(0.0),
          P::number("k", "-", "k of p_c = p_s + (1+k) p_t (Kratos KSIM; not in Ciantia et al. 2024 Table 2)").at_least(0.0).fallback(0.0),
      }),
  };
  return s;
}

const SectionDeclaration& pressure_keys() {
  static const SectionDeclaration s{.name = "fdm.boundary.pressure",
                                    .doc = "a pressure on the face group",
                                    .parameters = {P::number("pressure_pa", "Pa", "pressure, > 0 pushes into the body")}};
  return s;
}

const SectionDeclaration& traction_keys() {
  static const SectionDeclaration s{.name = "fdm.boundary.traction",
                                    .doc = "a traction on the face group",
                                    .parameters = {P::vector3("traction_pa", "Pa", "force per area on the face [tx, ty, tz]")}};
  return s;
}

}  // namespace

const SectionDeclaration& fdm_mesh() {
  static const SectionDeclaration s{
      .name = "fdm.mesh",
      .doc = "the continuum's mesh",
      .parameters = {P::string("type", "mesh generator").one_of({"box", "cylinder_cavity", "sphere_cavity_octant"})},
      .selector = "type",
      .variants = {{"box", box_keys().doc, &box_keys()},
                   {"cylinder_cavity", cylinder_cavity_keys().doc, &cylinder_cavity_keys()},
                   {"sphere_cavity_octant", sphere_cavity_octant_keys().doc, &sphere_cavity_octant_keys()}},
  };
  return s;
}

const SectionDeclaration& fdm_material() {
  static const SectionDeclaration s{
      .name = "fdm.material",
      .doc = "the constitutive model and its parameters, or a named material (preset) whose values the other keys override",
      .parameters = {P::string("preset", "a named material (fdm_server --help lists them)").optional("model and its parameters given here"),
                     P::string("model", "constitutive model")
                         .one_of({"elastic", "mohr_coulomb", "structured_cam_clay"})
                         .optional("the preset's model"),
                     P::number("density_kg_m3", "kg/m3", "mass density").positive().optional("the preset's density")},
      .selector = "model",
      .variants = {{"elastic", elastic_keys().doc, &elastic_keys()},
                   {"mohr_coulomb", mohr_coulomb_keys().doc, &mohr_coulomb_keys()},
                   {"structured_cam_clay", structured_cam_clay_keys().doc, &structured_cam_clay_keys()}},
  };
  return s;
}

const SectionDeclaration& fdm_damping() {
  static const SectionDeclaration s{
      .name = "fdm.damping",
      .doc = "numerical damping",
      .parameters = {P::number("local", "-", "local non-viscous damping alpha, < 1 (FLAC3D default 0.8)").within(Bounds{0.0, 1.0}).fallback(0.8)},
  };
  return s;
}

const SectionDeclaration& fdm_boundary() {
  static const SectionDeclaration s{
      .name = "fdm.boundary",
      .doc = "a condition on one face group",
      .parameters = {P::string("group", "face group of the mesh"),
                     P::string("condition", "fixed: all velocity components zero; roller: zero normal (or radial, about z) velocity")
                         .one_of({"fixed", "roller", "pressure", "traction"})},
      .selector = "condition",
      .variants = {{"fixed", "all velocity components zero", nullptr},
                   {"roller", "zero normal velocity (axis-aligned plane) or zero radial velocity (cylindrical group about z)", nullptr},
                   {"pressure", pressure_keys().doc, &pressure_keys()},
                   {"traction", traction_keys().doc, &traction_keys()}},
  };
  return s;
}

const SectionDeclaration& fdm_initial_stress() {
  static const SectionDeclaration s{
      .name = "fdm.initial_stress",
      .doc = "geostatic initial stress: sigma_v = rho |g| (z_top - z), sigma_h = K0 sigma_v (compression); needs gravity along -z",
      .parameters = {P::string("type", "stress profile").one_of({"geostatic"}),
                     P::number("k0", "-", "horizontal/vertical stress ratio K0").at_least(0.0),
                     P::number("z_top_m", "m", "height depth is measured from").optional("the top of the mesh")},
  };
  return s;
}

const SectionDeclaration& fdm_coupling() {
  static const SectionDeclaration s{
      .name = "fdm.coupling",
      .doc = "the coupling interface (provider: takes forces, returns velocities; driven: takes velocities, returns forces and masses)",
      .parameters = {P::string("role", "what the continuum does at the interface").one_of({"provider", "driven"}),
                     P::string("group", "face group the interface nodes lie on")},
  };
  return s;
}

const SectionDeclaration& fdm_server() {
  static const SectionDeclaration s{
      .name = "fdm_server",
      .doc = "explicit finite-difference continuum (FLAC3D-style mixed discretisation); stresses tension positive (Pa)",
      .parameters = {P::object("mesh", fdm_mesh()), P::object("material", fdm_material()),
                     P::vector3("gravity_m_s2", "m/s2", "total acceleration (the coupler passes N g here)").fallback({0.0, 0.0, 0.0}),
                     P::object("damping", fdm_damping()).optional("the damping section's defaults"),
                     P::boolean("mass_scaling", "scale inertial masses so any dt is stable (quasi-static); false: real masses, dt <= dt_max")
                         .fallback(true),
                     thread_count_declaration(), P::objects("boundaries", fdm_boundary()).optional("no boundary conditions"),
                     P::object("initial_stress", fdm_initial_stress()).optional("zero initial stress"),
                     P::object("coupling", fdm_coupling()).optional("standalone (no interface)")},
  };
  return s;
}

}  // namespace dfc::sections
