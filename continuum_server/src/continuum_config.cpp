#include "dfc/continuum/continuum_config.hpp"

#include <memory>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/common/sections/continuum_sections.hpp"
#include "dfc/constitutive/named_materials.hpp"
#include "dfc/continuum/pile_mesh.hpp"
#include "dfc/fdm/fdm_config.hpp"

namespace dfc::continuum {

namespace {

PileMeshSpec read_mesh(ConfigReader cfg, const RigidPileSpec& pile, PileModel& model) {
  PileMeshSpec spec;
  spec.radius = cfg.number("radius_m");
  spec.height = cfg.number("height_m");
  spec.pile_inner_radius = pile.inner_radius;
  spec.pile_outer_radius = pile.outer_radius;
  spec.bore_divisions = static_cast<Index>(cfg.integer("bore_divisions"));
  spec.wall_divisions = static_cast<Index>(cfg.integer("wall_divisions"));
  spec.outside_divisions = static_cast<Index>(cfg.integer("outside_divisions"));
  spec.radial_ratio = cfg.number("radial_ratio");
  spec.vertical_divisions = static_cast<Index>(cfg.integer("vertical_divisions"));
  spec.vertical_ratio = cfg.number("vertical_ratio");
  if (!(spec.radius > pile.outer_radius)) cfg.fail("radius_m", "must exceed pile.outer_radius_m");
  if (cfg.has("remesh_below_area_ratio")) model.remesh_below_area_ratio = cfg.number("remesh_below_area_ratio");
  model.remesh_refine_deg = cfg.number("remesh_refine_deg");
  cfg.finish();
  return spec;
}

RigidPileSpec read_pile(ConfigReader& cfg, std::optional<double>& stop_depth) {
  RigidPileSpec pile;
  pile.inner_radius = cfg.number("inner_radius_m");
  pile.outer_radius = cfg.number("outer_radius_m");
  if (!(pile.outer_radius > pile.inner_radius)) cfg.fail("outer_radius_m", "must exceed inner_radius_m");
  pile.velocity = cfg.number("step_m");
  pile.friction = cfg.number("friction");
  if (cfg.has("depth_m")) stop_depth = cfg.number("depth_m");
  cfg.finish();
  return pile;
}

}  // namespace

PileModel load_pile_model(const nlohmann::json& section) {
  ConfigReader root(section, "", sections::continuum_server());
  const std::array<double, 3> gravity = root.vec3("gravity_m_s2");
  if (gravity[0] != 0.0 || gravity[1] != 0.0 || gravity[2] != 0.0)
    root.fail("gravity_m_s2", "the continuum has no body force yet: set the scenario's gravity to 0 and give the stress level in initial_stress");
  std::optional<double> stop_depth;
  ConfigReader pile_cfg = root.child("pile");
  RigidPileSpec pile = read_pile(pile_cfg, stop_depth);
  PileModel model;
  const PileMeshSpec mesh_spec = read_mesh(root.child("mesh"), pile, model);
  pile.tip = mesh_spec.height;
  fdm::Material material = fdm::load_fdm_material(root.raw("material"));

  SolverSettings settings;
  settings.density = material.density;
  settings.damping = fdm::read_local_damping(root);
  double vertical = 0.0, k0 = 1.0;
  if (auto initial = root.optional_child("initial_stress")) {
    vertical = initial->number("vertical_pa");
    k0 = initial->number("k0");
    initial->finish();
  }
  root.finish();
  // Tension positive; xx = rr, yy = θθ, zz = zz (triangle_kinematics.hpp).
  const Stress initial_stress{-k0 * vertical, -k0 * vertical, -vertical, 0.0, 0.0, 0.0};
  AxisymmetricMesh soil = pile_mesh(mesh_spec);
  // The surface outside the pile's annulus: "top" less the edges the annulus
  // covers at the start, which the pile loads instead.
  auto& surface = soil.edge_groups["surface"];
  for (const Edge& e : soil.edge_group("top"))
    if (!(soil.nodes[e[0]].x() >= pile.inner_radius && soil.nodes[e[1]].x() >= pile.inner_radius &&
          soil.nodes[e[0]].x() <= pile.outer_radius && soil.nodes[e[1]].x() <= pile.outer_radius))
      surface.push_back(e);
  auto solver = std::make_unique<AxisymmetricSolver>(
      std::move(soil), std::shared_ptr<const constitutive::ConstitutiveModel>(std::move(material.model)), initial_stress, settings);
  const AxisymmetricMesh& mesh = solver->mesh();
  solver->prescribe_velocity(mesh.node_group("axis"), Axis::r, 0.0);
  solver->prescribe_velocity(mesh.node_group("outer"), Axis::r, 0.0);
  solver->prescribe_velocity(mesh.node_group("bottom"), Axis::z, 0.0);
  // The pressure that holds the uniform initial stress: the vertical stress
  // on the surface (the side is held radially, so its k0 σ_v is carried by
  // the support). Under the annulus the pile carries it from the first step.
  if (vertical > 0.0) solver->apply_pressure("surface", vertical);
  solver->set_pile(RigidPile(pile));
  model.solver = std::move(solver);
  model.stop_depth = stop_depth;
  model.pile_step = pile.velocity;
  return model;
}

std::string continuum_config_help() {
  return "  (a JSON object; unknown keys are errors, key paths are named in the error; the same keys are in scenario.schema.json)\n" +
         describe_section(sections::continuum_server()) + "Named materials (\"material.preset\"):\n" + constitutive::describe_named_materials();
}

}  // namespace dfc::continuum
