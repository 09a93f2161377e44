// Reading the fdm_server section (schema in fdm_config.hpp).
#include "dfc/fdm/fdm_config.hpp"

#include <algorithm>
#include <cmath>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/sections/fdm_sections.hpp"
#include "dfc/fdm/initial_stress.hpp"
#include "dfc/fdm/mesh_generators.hpp"
#include "dfc/constitutive/model_registry.hpp"
#include "dfc/constitutive/named_materials.hpp"

namespace dfc::fdm {

namespace {

// Each zone costs about 3 kB (10 tetrahedra with geometry, stress and forces).
constexpr std::int64_t kMaxZones = 5'000'000;

Vec3 to_vec3(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

void check_zone_total(ConfigReader& cfg, std::string_view key, double zones) {
  if (zones > double(kMaxZones))
    cfg.fail(key, "the mesh would have " + std::to_string(std::int64_t(zones)) + " zones; at most " + std::to_string(kMaxZones) +
                      " are allowed");
}

Mesh read_box(ConfigReader& cfg) {
  BoxSpec spec;
  spec.origin = to_vec3(cfg.vec3("origin_m"));
  spec.size = to_vec3(cfg.vec3("size_m"));
  const auto zones = cfg.integers3("zones");
  spec.zones = {Index(zones[0]), Index(zones[1]), Index(zones[2])};
  spec.grading = cfg.vec3("grading");
  check_zone_total(cfg, "zones", double(spec.zones[0]) * double(spec.zones[1]) * double(spec.zones[2]));
  return make_box(spec);
}

Mesh read_cylinder_cavity(ConfigReader& cfg) {
  CylinderCavitySpec spec;
  spec.inner_radius = cfg.number("inner_radius_m");
  spec.outer_radius = cfg.number("outer_radius_m");
  if (!(spec.outer_radius > spec.inner_radius)) cfg.fail("outer_radius_m", "must be larger than inner_radius_m");
  spec.z_bottom = cfg.number("z_bottom_m");
  spec.height = cfg.number("height_m");
  spec.zones_radial = Index(cfg.integer("zones_radial"));
  spec.zones_around = Index(cfg.integer("zones_around"));
  spec.zones_vertical = Index(cfg.integer("zones_vertical"));
  spec.grading_ratio = cfg.number("grading_ratio");
  spec.angle_deg = cfg.number("angle_deg");
  if (spec.angle_deg == 360.0 && spec.zones_around < 3) cfg.fail("zones_around", "the full circle needs zones_around >= 3");
  spec.max_aspect_ratio = cfg.number("max_aspect_ratio");
  // A floor at z_bottom_m (the default) is no floor: the cavity runs through
  // the whole height. Scenarios that include one with a base say so (an
  // include cannot delete a key).
  if (const double floor = cfg.has("cavity_floor_z_m") ? cfg.number("cavity_floor_z_m") : spec.z_bottom; floor != spec.z_bottom) {
    spec.cavity_floor_z = floor;
    if (const auto problem = cavity_floor_problem(spec)) cfg.fail(problem->key, problem->message);
  }
  check_zone_total(cfg, "zones_radial", double(spec.zones_radial) * double(spec.zones_around) * double(spec.zones_vertical));
  try {
    return make_cylinder_cavity(spec);
  } catch (const ConfigError&) {
    throw;
  } catch (const UserError& e) {
    cfg.fail("max_aspect_ratio", e.what());
  }
}

Mesh read_sphere_cavity_octant(ConfigReader& cfg) {
  SphereCavityOctantSpec spec;
  spec.inner_radius = cfg.number("inner_radius_m");
  spec.outer_radius = cfg.number("outer_radius_m");
  if (!(spec.outer_radius > spec.inner_radius)) cfg.fail("outer_radius_m", "must be larger than inner_radius_m");
  spec.zones_radial = Index(cfg.integer("zones_radial"));
  spec.zones_around = Index(cfg.integer("zones_around"));
  spec.grading_ratio = cfg.number("grading_ratio");
  spec.max_aspect_ratio = cfg.number("max_aspect_ratio");
  check_zone_total(cfg, "zones_radial", 3.0 * double(spec.zones_radial) * double(spec.zones_around) * double(spec.zones_around));
  try {
    return make_sphere_cavity_octant(spec);
  } catch (const ConfigError&) {
    throw;
  } catch (const UserError& e) {
    cfg.fail("max_aspect_ratio", e.what());
  }
}

Mesh read_mesh(ConfigReader cfg) {
  const std::string type = cfg.string("type");
  Mesh mesh = type == "box" ? read_box(cfg) : (type == "cylinder_cavity" ? read_cylinder_cavity(cfg) : read_sphere_cavity_octant(cfg));
  cfg.finish();
  return mesh;
}

Material read_model_and_parameters(ConfigReader cfg) {
  if (!cfg.has("model")) cfg.fail("model", "missing: give \"model\" and its parameters, or a \"preset\" (fdm_server --help lists both)");
  const std::string keyword = cfg.string("model");
  const constitutive::ConstitutiveModelEntry* entry = constitutive::find_constitutive_model(keyword);
  if (entry == nullptr) {
    std::string known;
    for (const auto& e : constitutive::constitutive_models()) known += (known.empty() ? "\"" : ", \"") + std::string(e.keyword) + "\"";
    cfg.fail("model", "unknown constitutive model \"" + keyword + "\"; known models: " + known);
  }
  Material material;
  if (!cfg.has("density_kg_m3")) cfg.fail("density_kg_m3", "missing required key (mass density, kg/m3)");
  material.density = cfg.number("density_kg_m3");
  try {
    material.model = entry->create(cfg);
  } catch (const ConfigError&) {
    throw;
  } catch (const UserError& e) {
    cfg.fail("model", e.what());
  }
  cfg.finish();
  return material;
}

// "preset": a named material (named_materials.hpp) whose values the other keys
// of the object override; the expanded object is then read as usual, so
// errors still name "material.<key>".
Material read_material(const nlohmann::json& given) {
  if (!given.is_object() || !given.contains("preset"))
    return read_model_and_parameters(ConfigReader(given, "material", sections::fdm_material()));
  ConfigReader cfg(given, "material", sections::fdm_material());
  const std::string name = cfg.string("preset");
  const constitutive::NamedMaterial* preset = constitutive::find_named_material(name);
  if (preset == nullptr) {
    std::string known;
    for (const auto& m : constitutive::named_materials()) known += (known.empty() ? "\"" : ", \"") + std::string(m.name) + "\"";
    cfg.fail("preset", "unknown named material \"" + name + "\"; known: " + known);
  }
  const nlohmann::json expanded = constitutive::expand_named_material(*preset, given);
  return read_model_and_parameters(ConfigReader(expanded, "material", sections::fdm_material()));
}

SolverSettings read_settings(ConfigReader& root) {
  SolverSettings settings;
  settings.gravity = to_vec3(root.vec3("gravity_m_s2"));
  settings.local_damping = read_local_damping(root);
  settings.mass_scaling = root.boolean("mass_scaling");
  settings.threads = read_thread_count(root);
  return settings;
}

BoundaryCondition read_boundary(ConfigReader& entry, const Mesh& mesh) {
  BoundaryCondition condition;
  condition.group = entry.string("group");
  if (!mesh.has_face_group(condition.group))
    entry.fail("group", "unknown face group \"" + condition.group + "\"; this mesh has " + mesh.face_group_names());
  const std::string kind = entry.string("condition");
  if (kind == "fixed") condition.kind = BoundaryKind::fixed;
  if (kind == "roller") condition.kind = BoundaryKind::roller;
  if (kind == "pressure") {
    condition.kind = BoundaryKind::pressure;
    condition.pressure = entry.number("pressure_pa");
  }
  if (kind == "traction") {
    condition.kind = BoundaryKind::traction;
    condition.traction = to_vec3(entry.vec3("traction_pa"));
  }
  entry.finish();
  return condition;
}

void read_initial_stress(ConfigReader cfg, Solver& solver) {
  [[maybe_unused]] const std::string type = cfg.string("type");  // "geostatic", the only profile so far
  GeostaticStress profile;
  profile.k0 = cfg.number("k0");
  profile.z_top = cfg.has("z_top_m") ? cfg.number("z_top_m") : solver.mesh().max_z();
  cfg.finish();
  const Vec3 g = solver.settings().gravity;
  if (g.x() != 0.0 || g.y() != 0.0 || g.z() > 0.0)
    cfg.fail("type", "geostatic initial stress needs gravity_m_s2 pointing along -z (depth is measured down from z_top_m)");
  const double density = solver.density();
  const double g_magnitude = g.norm();
  solver.set_initial_stress([&](const Vec3& centroid) { return geostatic_stress(profile, density, g_magnitude, centroid.z()); });
}

CouplingSettings read_coupling(ConfigReader cfg, const Mesh& mesh) {
  CouplingSettings coupling;
  coupling.role = cfg.string("role") == "provider" ? CouplingRole::provider : CouplingRole::driven;
  coupling.group = cfg.string("group");
  if (!mesh.has_face_group(coupling.group))
    cfg.fail("group", "unknown face group \"" + coupling.group + "\"; this mesh has " + mesh.face_group_names());
  cfg.finish();
  return coupling;
}

}  // namespace

Material load_fdm_material(const nlohmann::json& material) { return read_material(material); }

double read_local_damping(ConfigReader& root) {
  double local = sections::fdm_damping().find("local")->default_value.get<double>();
  if (auto damping = root.optional_child("damping")) {
    local = damping->number("local");
    if (!(local < 1.0)) damping->fail("local", "expected a number in [0, 1), got 1 (no net force would remain)");
    damping->finish();
  }
  return local;
}

FdmModel load_fdm_model(const nlohmann::json& section) {
  ConfigReader root(section, "", sections::fdm_server());
  Mesh mesh = read_mesh(root.child("mesh"));
  Material material = read_material(root.raw("material"));
  const SolverSettings settings = read_settings(root);

  std::optional<Solver> solver;
  try {
    solver.emplace(std::move(mesh), std::move(material), settings);
  } catch (const ConfigError&) {
    throw;
  } catch (const UserError& e) {
    throw ConfigError("mesh", e.what());
  }

  if (root.has("boundaries")) {
    for (ConfigReader& entry : root.children("boundaries")) {
      const BoundaryCondition condition = read_boundary(entry, solver->mesh());
      try {
        solver->apply_boundary_condition(condition);
      } catch (const UserError& e) {
        entry.fail("condition", e.what());
      }
    }
  } else {
    root.accept("boundaries");
  }
  if (auto initial = root.optional_child("initial_stress")) read_initial_stress(std::move(*initial), *solver);
  CouplingSettings coupling;
  if (auto cfg = root.optional_child("coupling")) coupling = read_coupling(std::move(*cfg), solver->mesh());
  root.finish();
  return FdmModel{std::move(*solver), std::move(coupling)};
}

}  // namespace dfc::fdm
