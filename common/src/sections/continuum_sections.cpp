// The continuum_server section, declared once (continuum_sections.hpp). The
// material is fdm_server's (the shared dfc_constitutive models and presets).
#include "dfc/common/sections/continuum_sections.hpp"

#include "dfc/common/sections/fdm_sections.hpp"

namespace dfc::sections {

namespace {

using P = ParameterDeclaration;

}  // namespace

const SectionDeclaration& continuum_mesh() {
  static const SectionDeclaration s{
      .name = "continuum.mesh",
      .doc = "the soil cylinder 0 <= r <= radius_m, 0 <= z <= height_m (axisymmetric, linear triangles), node columns at the pile's "
             "radii, fine at the pile's wall and at the surface; node groups axis, outer, bottom (fixed in z), top (the surface)",
      .parameters = {P::number("radius_m", "m", "radius of the soil cylinder (the container), > the pile's outer radius").positive(),
                     P::number("height_m", "m", "height of the soil; the surface z = height_m is where the pile's tip starts").positive(),
                     P::integer("bore_divisions", "elements across the bore 0 <= r <= r_i, graded fine at r_i").integer_within(1).fallback(6),
                     P::integer("wall_divisions", "elements across the pile's wall r_i <= r <= r_o, uniform").integer_within(1).fallback(4),
                     P::integer("outside_divisions", "elements from r_o to radius_m, graded fine at r_o").integer_within(1).fallback(20),
                     P::number("radial_ratio", "-", "growth of the radial spacing away from the pile's wall").at_least(1.0).fallback(1.15),
                     P::integer("vertical_divisions", "elements from the surface to the base").integer_within(1).fallback(30),
                     P::number("vertical_ratio", "-", "growth of the vertical spacing downwards from the surface").at_least(1.0).fallback(1.1),
                     P::number("remesh_below_area_ratio", "-",
                               "after an exchange in which a triangle's area fell below this fraction of its area when it was made, "
                               "re-triangulate the nodes (constrained Delaunay)")
                         .within(Bounds{0.0, 1.0, true})
                         .optional("the mesh is never remeshed"),
                     P::number("remesh_refine_deg", "deg", "with remeshing: refine the new triangulation until no angle is below this (adds nodes)")
                         .within(Bounds{0.0, 30.0})
                         .fallback(0.0)},
  };
  return s;
}

const SectionDeclaration& continuum_pile() {
  static const SectionDeclaration s{
      .name = "continuum.pile",
      .doc = "the rigid open-ended pile (a tube above a flat annulus, its tip starting on the surface) jacked down at a constant "
             "displacement per step; frictional contact on the annulus and both shafts (docs/continuum_pile.md section 6)",
      .parameters = {P::number("inner_radius_m", "m", "inner radius r_i of the tube (0: a solid punch)").at_least(0.0),
                     P::number("outer_radius_m", "m", "outer radius r_o of the tube, > inner_radius_m").positive(),
                     P::number("step_m", "m", "downward displacement per solver step (quasi-static pseudo-time)").positive(),
                     P::number("depth_m", "m", "penetration at which the pile stops and is held").positive().optional("it never stops"),
                     P::number("friction", "-", "Coulomb coefficient mu = tan(delta) of the pile-soil interface").at_least(0.0)},
  };
  return s;
}

const SectionDeclaration& continuum_initial_stress() {
  static const SectionDeclaration s{
      .name = "continuum.initial_stress",
      .doc = "a uniform initial stress, held by the same pressures on the surface (vertical) and the side (k0 x vertical); no gravity",
      .parameters = {P::number("vertical_pa", "Pa", "vertical effective stress, compression positive").at_least(0.0),
                     P::number("k0", "-", "horizontal over vertical stress").at_least(0.0).fallback(1.0)},
  };
  return s;
}

const SectionDeclaration& continuum_server() {
  static const SectionDeclaration s{
      .name = "continuum_server",
      .doc = "axisymmetric large-strain continuum of a jacked open-ended pile (updated Lagrangian linear triangles, Jaumann rate, "
             "explicit dynamic relaxation, Dohrmann-Bochev pressure projection; drained); stresses tension positive (Pa)",
      .parameters = {P::object("mesh", continuum_mesh()), P::object("material", fdm_material()), P::object("pile", continuum_pile()),
                     P::object("initial_stress", continuum_initial_stress()).optional("zero initial stress"),
                     P::vector3("gravity_m_s2", "m/s2", "must be zero: the continuum has no body force yet (the coupler passes N g here)")
                         .fallback({0.0, 0.0, 0.0}),
                     P::object("damping", fdm_damping()).optional("the damping section's defaults")},
  };
  return s;
}

}  // namespace dfc::sections
