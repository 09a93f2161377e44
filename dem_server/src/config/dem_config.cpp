#include "dfc/dem/dem_config.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/dem/region_config.hpp"
#include "dfc/dem/ucs_platens.hpp"

namespace dfc::dem {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

Vec3 to_vec3(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

/// Upscaling by S multiplies every generated radius by S and applies each
/// law's declared rule (contact_law_registry.hpp, upscale()).
ContactLawSetting read_upscaled_law(ConfigReader cfg, double scale_factor) {
  return upscale(read_contact_law(std::move(cfg)), scale_factor);
}

double read_scale_factor(ConfigReader& section) {
  auto upscaling = section.optional_child("upscaling");
  if (!upscaling) return 1.0;
  const double s = upscaling->positive("scale_factor");
  upscaling->finish();
  return s;
}

ParticleConfig read_particles(ConfigReader cfg, double scale_factor) {
  ParticleConfig p;
  p.generator = cfg.choice("generator", {"lattice", "list", "radius_expansion", "pcrm"});
  p.density = cfg.positive("density_kg_m3");
  if (p.generator == "lattice") {
    p.lattice.radius_min = scale_factor * cfg.positive("radius_min_m");
    p.lattice.radius_max = scale_factor * cfg.positive("radius_max_m");
    if (p.lattice.radius_max < p.lattice.radius_min) cfg.fail("radius_max_m", "must be at least radius_min_m");
    p.lattice.spacing_factor = cfg.number("spacing_factor", 1.05, Bounds{1.0, 10.0});
    p.lattice.arrangement =
        cfg.choice("arrangement", {"cubic", "fcc"}, "cubic") == "fcc" ? LatticeArrangement::fcc : LatticeArrangement::cubic;
    p.lattice.seed = std::uint64_t(cfg.integer("seed", 1, 0));
    p.lattice.region = read_region(cfg.child("region"));
    p.spheres = generate_lattice_bed(p.lattice);
    if (p.spheres.empty()) cfg.fail("region", "no sphere fits: the region must be at least 2 radius_max_m x spacing_factor wide in every direction");
  } else if (p.generator == "pcrm") {
    p.pcrm = read_pcrm(cfg, scale_factor, p.density);
  } else if (p.generator == "radius_expansion") {
    p.expansion = read_radius_expansion(cfg);  // placed once the periodic cell is known (parse_dem_config)
    p.expansion.radius_min *= scale_factor;    // the cell stays: upscaling means fewer, larger spheres
    p.expansion.radius_max *= scale_factor;
  } else {
    if (scale_factor != 1.0)
      cfg.fail("generator", "\"list\" spheres are taken as given, so upscaling.scale_factor must be 1 with it; give the upscaled radii in the list or use a generator");
    const nlohmann::json& list = cfg.raw("spheres");
    if (!list.is_array() || list.empty()) cfg.fail("spheres", "expected a non-empty array of [x, y, z, radius] in m");
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::string key = "spheres[" + std::to_string(k) + "]";
      const auto& s = list[k];
      if (!s.is_array() || s.size() != 4 || !std::all_of(s.begin(), s.end(), [](const auto& v) { return v.is_number(); }))
        cfg.fail(key, "expected [x, y, z, radius] in m");
      const GeneratedSphere sphere{{s[0].get<double>(), s[1].get<double>(), s[2].get<double>()}, s[3].get<double>()};
      if (!is_finite(sphere.centre) || !(sphere.radius > 0.0) || !std::isfinite(sphere.radius))
        cfg.fail(key, "expected finite coordinates and a positive radius");
      p.spheres.push_back(sphere);
    }
  }
  cfg.finish();
  return p;
}

/// Bounding box of the spheres, for default wall sizes.
std::pair<Vec3, Vec3> bounding_box(const std::vector<GeneratedSphere>& spheres) {
  Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  for (const auto& s : spheres) {
    const Vec3 r{s.radius, s.radius, s.radius};
    const Vec3 a = s.centre - r, b = s.centre + r;
    lo = {std::min(lo.x, a.x), std::min(lo.y, a.y), std::min(lo.z, a.z)};
    hi = {std::max(hi.x, b.x), std::max(hi.y, b.y), std::max(hi.z, b.z)};
  }
  return {lo, hi};
}

ContactLawSetting read_optional_contact(ConfigReader& cfg, const ContactLawSetting& fallback, double scale_factor) {
  auto child = cfg.optional_child("contact");
  return child ? read_upscaled_law(std::move(*child), scale_factor) : fallback;
}

std::string read_wall_name(ConfigReader& cfg, std::size_t index, std::set<std::string>& used) {
  std::string name = cfg.string("name", "wall" + std::to_string(index));
  const bool valid = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
  if (!valid) cfg.fail("name", "use letters, digits and '_' only (it becomes part of monitor names)");
  if (name == "pile" || name == "interface") cfg.fail("name", "\"" + name + "\" is reserved for the pile and the coupling wall");
  if (!used.insert(name).second) cfg.fail("name", "another wall is already called \"" + name + "\"");
  return name;
}

WallMesh read_facet_mesh(ConfigReader& cfg) {
  WallMesh mesh;
  const nlohmann::json& vertices = cfg.raw("vertices_m");
  if (!vertices.is_array() || vertices.size() < 3) cfg.fail("vertices_m", "expected an array of at least 3 [x, y, z] in m");
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const auto& v = vertices[k];
    if (!v.is_array() || v.size() != 3 || !std::all_of(v.begin(), v.end(), [](const auto& e) { return e.is_number(); }))
      cfg.fail("vertices_m[" + std::to_string(k) + "]", "expected [x, y, z] in m");
    mesh.vertices.push_back({v[0].get<double>(), v[1].get<double>(), v[2].get<double>()});
  }
  const nlohmann::json& facets = cfg.raw("facets");
  if (!facets.is_array() || facets.empty()) cfg.fail("facets", "expected an array of [i, j, k] vertex indices");
  for (std::size_t k = 0; k < facets.size(); ++k) {
    const auto& f = facets[k];
    const bool ok = f.is_array() && f.size() == 3 && std::all_of(f.begin(), f.end(), [&](const auto& e) {
      return e.is_number_integer() && e.template get<std::int64_t>() >= 0 && e.template get<std::int64_t>() < std::int64_t(vertices.size());
    });
    if (!ok) cfg.fail("facets[" + std::to_string(k) + "]", "expected [i, j, k] with indices into vertices_m (0.." + std::to_string(vertices.size() - 1) + ")");
    mesh.facets.push_back({f[0].get<std::uint32_t>(), f[1].get<std::uint32_t>(), f[2].get<std::uint32_t>()});
  }
  try {
    validate_mesh(mesh, cfg.path());
  } catch (const UserError& e) {
    cfg.fail("facets", e.what());
  }
  return mesh;
}

WallConfig read_wall(ConfigReader cfg, std::size_t index, std::set<std::string>& used, const ContactLawSetting& wall_contact,
                     const std::pair<Vec3, Vec3>& particle_box, double scale_factor) {
  WallConfig wall;
  const std::string type = cfg.choice("type", {"plane", "facets"});
  wall.name = read_wall_name(cfg, index, used);
  if (type == "plane") {
    const Vec3 point = to_vec3(cfg.vec3("point_m"));
    const Vec3 normal = to_vec3(cfg.vec3("normal"));
    if (!(norm(normal) > 0.0)) cfg.fail("normal", "must not be the zero vector");
    // Default size: covers the particles' bounding box seen from the point,
    // generously; none when the particles are generated later inside the walls.
    const Vec3 centre = 0.5 * (particle_box.first + particle_box.second);
    const double fallback = norm(centre - point) + norm(particle_box.second - particle_box.first);
    wall.mesh = make_plane_mesh(point, normal, std::isfinite(fallback) ? cfg.positive("half_size_m", fallback) : cfg.positive("half_size_m"));
  } else {
    wall.mesh = read_facet_mesh(cfg);
  }
  wall.velocity = to_vec3(cfg.vec3("velocity_m_s", {0.0, 0.0, 0.0}));
  wall.start_step = cfg.integer("start_step", 0, 0);
  wall.contact = read_optional_contact(cfg, wall_contact, scale_factor);
  cfg.finish();
  return wall;
}

PileConfig read_pile(ConfigReader cfg, const ContactLawSetting& wall_contact, double scale_factor) {
  PileConfig pile;
  const auto axis = read_xy(cfg, "axis_xy_m");
  pile.geometry.axis_x = axis[0];
  pile.geometry.axis_y = axis[1];
  pile.geometry.radius = cfg.positive("radius_m");
  pile.geometry.tip_z = cfg.number("tip_z_m");
  pile.geometry.length = cfg.positive("length_m");
  // A 1000-sided prism is within 5e-6 of the circle; more sides only cost memory (1e8 exhausted it).
  pile.geometry.sides = int(cfg.integer("sides", 24, 3, 1000));
  if (cfg.has("wall_thickness_m")) {  // an open-ended tube (wall_builders.hpp)
    const double thickness = cfg.positive("wall_thickness_m");
    if (!(thickness < pile.geometry.radius))
      cfg.fail("wall_thickness_m", "must be less than radius_m (the tube's outer radius); omit it for a closed pile");
    pile.geometry.inner_radius = pile.geometry.radius - thickness;
  }
  pile.velocity = to_vec3(cfg.vec3("velocity_m_s", {0.0, 0.0, 0.0}));
  pile.start_step = cfg.integer("start_step", 0, 0);
  if (auto when = cfg.optional_child("start_when")) {
    const double ratio = when->number("unbalanced_force_ratio", Bounds{0.0, 1.0, true});
    if (!(ratio > 0.0)) when->fail("unbalanced_force_ratio", "expected a ratio in (0, 1), e.g. 0.002 (the generation's run.stop_when)");
    pile.start_when = PileStartRule{ratio};
    when->finish();
  }
  pile.ramp_steps = cfg.integer("ramp_steps", 0, 0);
  pile.contact = read_optional_contact(cfg, wall_contact, scale_factor);
  cfg.finish();
  return pile;
}

std::size_t find_wall(ConfigReader& cfg, std::string_view key, const std::vector<WallConfig>& walls) {
  const std::string name = cfg.string(key);
  for (std::size_t k = 0; k < walls.size(); ++k)
    if (walls[k].name == name) return k;
  cfg.fail(key, "no wall is called \"" + name + "\"; name one of the \"walls\"");
}

/// Cross-section of the sample normal to z: a disc through the outermost
/// particle of a cylindrical bed, the particles' x–y bounding box of a box bed.
/// Returns 0 when it cannot be derived (listed spheres, an axis other than z).
double derived_area(const ParticleConfig& p, const PlatenAxis& axis) {
  if (p.generator != "lattice" || std::abs(std::abs(axis.axis.z) - 1.0) > 1e-9) return 0.0;
  const BedRegion& r = p.lattice.region;
  if (r.shape == BedRegion::Shape::cylinder) {
    double radius = 0.0;
    for (const auto& s : p.spheres) radius = std::max(radius, std::hypot(s.centre.x - r.axis_x, s.centre.y - r.axis_y) + s.radius);
    return std::numbers::pi * radius * radius;
  }
  const auto [lo, hi] = bounding_box(p.spheres);
  return (hi.x - lo.x) * (hi.y - lo.y);
}

/// Moves both platens along the axis until each touches the outermost particle
/// surface (support function max/min of c.a ± r), so that loading starts at
/// once instead of after closing the lattice's margin to the region faces.
void seat_platens(WallConfig& top, WallConfig& bottom, const std::vector<GeneratedSphere>& spheres, const PlatenAxis& axis) {
  double high = -inf, low = inf;
  for (const auto& s : spheres) {
    high = std::max(high, dot(s.centre, axis.axis) + s.radius);
    low = std::min(low, dot(s.centre, axis.axis) - s.radius);
  }
  const auto shift = [&](WallConfig& wall, double target) {
    const Vec3 delta = (target - dot(vertex_centroid(wall.mesh.vertices), axis.axis)) * axis.axis;
    for (auto& v : wall.mesh.vertices) v += delta;
  };
  shift(top, high);
  shift(bottom, low);
}

UcsConfig read_ucs(ConfigReader cfg, DemConfig& c) {
  UcsConfig ucs;
  ucs.top_wall = find_wall(cfg, "top_wall", c.walls);
  ucs.bottom_wall = find_wall(cfg, "bottom_wall", c.walls);
  if (ucs.top_wall == ucs.bottom_wall) cfg.fail("bottom_wall", "must differ from top_wall");
  WallConfig& top = c.walls[ucs.top_wall];
  WallConfig& bottom = c.walls[ucs.bottom_wall];
  PlatenAxis axis;
  try {
    axis = platen_axis(top.mesh.vertices, bottom.mesh.vertices);
  } catch (const UserError& e) {
    cfg.fail("top_wall", e.what());
  }
  if (cfg.has("area_m2")) {
    ucs.area = cfg.positive("area_m2");
  } else {
    cfg.accept("area_m2");
    ucs.area = derived_area(c.particles, axis);
    if (!(ucs.area > 0.0)) cfg.fail("area_m2", "cannot be derived (listed spheres or platens not normal to z); give the sample cross-section in m2");
  }
  ucs.start_step = cfg.integer("start_step", 0, 0);
  if (cfg.boolean("seat_platens", true)) {
    seat_platens(top, bottom, c.particles.spheres, axis);
    axis = platen_axis(top.mesh.vertices, bottom.mesh.vertices);
  }
  if (cfg.has("strain_rate_per_s")) {
    ucs.strain_rate = cfg.positive("strain_rate_per_s");
    if (norm(top.velocity) > 0.0 || norm(bottom.velocity) > 0.0)
      cfg.fail("strain_rate_per_s", "the platens already have a velocity_m_s; give either the strain rate or the wall velocities");
    // Each platen moves half the closing speed dH/dt = -rate H0, so the sample
    // centre stays put and the platens load it symmetrically.
    const double speed = 0.5 * *ucs.strain_rate * axis.initial_height;
    top.velocity = -speed * axis.axis;
    bottom.velocity = speed * axis.axis;
    top.start_step = bottom.start_step = ucs.start_step;
  } else {
    cfg.accept("strain_rate_per_s");
  }
  cfg.finish();
  return ucs;
}

/// The meshes of the six walls in TriaxialWalls::in_order().
BoxVertices config_box_vertices(const std::vector<WallConfig>& walls, const TriaxialWalls& box) {
  BoxVertices v;
  const auto order = box.in_order();
  for (std::size_t k = 0; k < 6; ++k) v[k] = walls[order[k]].mesh.vertices;
  return v;
}

TriaxialConfig read_triaxial(ConfigReader cfg, DemConfig& c) {
  if (c.periodic) cfg.fail("top_wall", "a periodic cell has no walls to confine; use periodic.loading with mode \"triaxial\" instead");
  if (c.ucs) cfg.fail("top_wall", "give either a \"ucs\" or a \"triaxial\" section, not both");
  TriaxialConfig t;
  t.walls.top = find_wall(cfg, "top_wall", c.walls);
  t.walls.bottom = find_wall(cfg, "bottom_wall", c.walls);
  const std::vector<std::string> lateral = cfg.strings("lateral_walls");
  if (lateral.size() != 4)
    cfg.fail("lateral_walls", "name four walls: the two of one opposite pair, then the two of the other, e.g. [\"x_min\", \"x_max\", \"y_min\", \"y_max\"]");
  std::set<std::size_t> used{t.walls.top, t.walls.bottom};
  for (std::size_t k = 0; k < 4; ++k) {
    const auto it = std::find_if(c.walls.begin(), c.walls.end(), [&](const WallConfig& w) { return w.name == lateral[k]; });
    if (it == c.walls.end()) cfg.fail("lateral_walls", "no wall is called \"" + lateral[k] + "\"; name four of the \"walls\"");
    t.walls.lateral[k] = std::size_t(it - c.walls.begin());
    used.insert(t.walls.lateral[k]);
  }
  if (used.size() != 6) cfg.fail("lateral_walls", "the platens and the four lateral walls must be six different walls");
  for (const std::size_t w : used)
    if (norm(c.walls[w].velocity) > 0.0 || c.walls[w].start_step != 0)
      cfg.fail("top_wall", "wall \"" + c.walls[w].name + "\" has a velocity_m_s or start_step; the triaxial servo drives all six walls, remove them");
  BoxAxes axes;
  try {
    axes = box_axes(config_box_vertices(c.walls, t.walls));
  } catch (const UserError& e) {
    cfg.fail("lateral_walls", e.what());
  }
  // Every wall onto the outermost particles along its normal; a radius
  // expansion fills the walls as they stand instead.
  if (cfg.boolean("seat_walls", true) && !c.particles.spheres.empty()) {
    seat_platens(c.walls[t.walls.top], c.walls[t.walls.bottom], c.particles.spheres, {axes.axis, 0.0});
    for (std::size_t p = 0; p < 2; ++p)
      seat_platens(c.walls[t.walls.lateral[2 * p + 1]], c.walls[t.walls.lateral[2 * p]], c.particles.spheres, {axes.lateral[p], 0.0});
  }
  t.confining_stress = cfg.positive("confining_stress_pa");
  t.strain_rate = cfg.positive("strain_rate_per_s");
  if (auto servo = cfg.optional_child("servo")) {
    t.servo_gain = servo->number("gain", 0.5, Bounds{0.0, 1.0, true});
    if (servo->has("max_strain_rate_per_s")) t.max_strain_rate = servo->positive("max_strain_rate_per_s");
    else servo->accept("max_strain_rate_per_s");
    servo->finish();
  }
  if (auto confinement = cfg.optional_child("confinement")) {
    t.confinement = read_equilibrium_target(*confinement);
    confinement->finish();
  }
  cfg.finish();
  return t;
}

TimestepConfig read_timestep(ConfigReader& root) {
  TimestepConfig t;
  auto cfg = root.optional_child("timestep");
  if (!cfg) return t;
  if (cfg->has("dt_s") && cfg->has("fraction_of_critical")) cfg->fail("dt_s", "give either dt_s or fraction_of_critical, not both");
  if (cfg->has("dt_s")) t.dt = cfg->positive("dt_s");
  t.fraction_of_critical = cfg->number("fraction_of_critical", 0.2, Bounds{0.0, 1.0, true});
  cfg->finish();
  return t;
}

/// Radius expansion: places the spheres in the cell; every periodic edge must
/// hold 2 (2 r_max + reach) with the final radii.
void read_periodic_particles(DemConfig& c, const std::string& periodic_path) {
  ParticleConfig& p = c.particles;
  double r_max = 0.0;
  if (p.generator == "radius_expansion") {
    try {
      ExpansionPacking packing = place_for_radius_expansion(p.expansion, c.periodic->cell);
      p.spheres = std::move(packing.spheres);
      p.final_radius = std::move(packing.final_radius);
    } catch (const UserError& e) {
      throw ConfigError("particles.multiplier", e.what());
    }
    for (const double r : p.final_radius) r_max = std::max(r_max, r);
  } else {
    for (const auto& s : p.spheres) r_max = std::max(r_max, s.radius);
  }
  const double skin = c.skin > 0.0 ? c.skin : 0.2 * r_max;
  check_periodic_width(*c.periodic, r_max, std::max(skin, c.contact.bond_gap()), periodic_path);
}

/// Radius expansion inside the six walls of a triaxial section: the box their
/// centroids bound (walls normal to x, y and z; each centroid is the lowest or
/// highest of the six along its own normal, the middle along the others) as a
/// cell with no periodic axis, so the placement keeps whole spheres inside it.
void place_in_walls(DemConfig& c) {
  if (!c.triaxial)
    throw ConfigError("particles.generator",
                      "\"radius_expansion\" fills a periodic cell or the six walls of a triaxial section: add a \"periodic\" block with min_m and "
                      "max_m, or a \"triaxial\" section");
  const BoxVertices vertices = config_box_vertices(c.walls, c.triaxial->walls);
  const BoxAxes axes = box_axes(vertices);
  for (const Vec3& a : {axes.axis, axes.lateral[0], axes.lateral[1]})
    if (std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)}) < 1.0 - 1e-12)
      throw ConfigError("triaxial.lateral_walls", "a radius expansion inside the walls needs the six walls normal to x, y or z");
  PeriodicCell box{.lo = {inf, inf, inf}, .hi = {-inf, -inf, -inf}, .periodic = {false, false, false}, .strain_rate = {}};
  for (const auto& v : vertices) {
    const Vec3 x = vertex_centroid(v);
    box.lo = {std::min(box.lo.x, x.x), std::min(box.lo.y, x.y), std::min(box.lo.z, x.z)};
    box.hi = {std::max(box.hi.x, x.x), std::max(box.hi.y, x.y), std::max(box.hi.z, x.z)};
  }
  try {
    ExpansionPacking packing = place_for_radius_expansion(c.particles.expansion, box);
    c.particles.spheres = std::move(packing.spheres);
    c.particles.final_radius = std::move(packing.final_radius);
  } catch (const UserError& e) {
    throw ConfigError("particles.multiplier", e.what());
  }
}

}  // namespace

DemConfig parse_dem_config(const nlohmann::json& section) {
  ConfigReader cfg(section, "");
  DemConfig c;
  c.scale_factor = read_scale_factor(cfg);
  c.particles = read_particles(cfg.child("particles"), c.scale_factor);
  const ContactLawSetting contact = read_contact_law(cfg.child("contact"));
  if (c.particles.pcrm && !c.particles.pcrm->zones.empty()) {  // graded: the first zone's S is the section's
    const auto& zones = c.particles.pcrm->zones;
    c.scale_factor = zones.front().scale_factor;
    for (std::size_t k = 1; k < zones.size(); ++k) c.material_laws.push_back(upscale(contact, zones[k].scale_factor));
  }
  c.contact = upscale(contact, c.scale_factor);
  auto wall_contact = cfg.optional_child("wall_contact");
  c.wall_contact = wall_contact ? read_upscaled_law(std::move(*wall_contact), c.scale_factor) : c.contact;
  if (auto damping = cfg.optional_child("damping")) {
    c.local_damping = damping->number("local", 0.7, Bounds{0.0, 1.0});
    if (c.local_damping >= 1.0) damping->fail("local", "must be below 1 (1 would cancel every driving force)");
    damping->finish();
  }
  c.timestep = read_timestep(cfg);
  c.gravity = to_vec3(cfg.vec3("gravity_m_s2", {0.0, 0.0, 0.0}));
  if (auto neighbour = cfg.optional_child("neighbour")) {
    if (neighbour->has("skin_m")) c.skin = neighbour->positive("skin_m");
    else neighbour->accept("skin_m");
    neighbour->finish();
  }
  if (auto periodic = cfg.optional_child("periodic")) {
    if (c.particles.pcrm) periodic->fail("min_m", "generator \"pcrm\" prepares its own periodic REV (particles.rev) and fills particles.region; remove \"periodic\"");
    const std::string path = periodic->path().empty() ? "" : periodic->path() + ".";
    c.periodic = read_periodic_config(std::move(*periodic));
    read_periodic_particles(c, path);
  } else {
    cfg.accept("periodic");
  }
  const auto box = c.particles.pcrm ? region_bounds(c.particles.pcrm->region) : bounding_box(c.particles.spheres);
  if (cfg.has("walls")) {
    std::set<std::string> names;
    auto walls = cfg.children("walls");
    for (std::size_t k = 0; k < walls.size(); ++k) c.walls.push_back(read_wall(std::move(walls[k]), k, names, c.wall_contact, box, c.scale_factor));
  } else {
    cfg.accept("walls");
  }
  if (auto pile = cfg.optional_child("pile")) c.pile = read_pile(std::move(*pile), c.wall_contact, c.scale_factor);
  if (auto ucs = cfg.optional_child("ucs")) c.ucs = read_ucs(std::move(*ucs), c);
  if (auto triaxial = cfg.optional_child("triaxial")) c.triaxial = read_triaxial(std::move(*triaxial), c);
  if (c.particles.generator == "radius_expansion" && !c.periodic) place_in_walls(c);
  c.threads = read_thread_count(cfg);
  cfg.finish();
  return c;
}

std::string dem_config_help() {
  return R"((SI units; unknown keys are errors)
  particles       (required) the spheres
    generator       "lattice" | "list" | "radius_expansion" (needs "periodic" or "triaxial") | "pcrm"
    density_kg_m3   particle density (required)
    lattice: radius_min_m, radius_max_m (required), spacing_factor (1.05: lattice pitch / 2 radius_max_m),
             arrangement ("cubic" | "fcc": close-packed layers, a denser start that settles faster),
             seed (1), region (required):
               {"type":"box", "min_m":[x,y,z], "max_m":[x,y,z]} or
               {"type":"cylinder", "radius_m", "z_min_m", "z_max_m", "axis_xy_m":[0,0]}
    list:    spheres: [[x, y, z, radius], ...]
    radius_expansion (docs/dem_periodic.md): radius_min_m, radius_max_m (required; final radii, uniform; an upscaled
             run multiplies them by S), porosity (required: target in (0,1), met exactly after the last stage),
             multiplier (1.6: final/initial radius), stages (10), relax_steps (1000 cycles after each stage),
             seed (1); spheres are placed at random without overlap at radius/multiplier in the periodic cell
             (or the box of the triaxial walls)
)" + pcrm_help() + R"(  upscaling       {"scale_factor": S} particle upscaling (default S = 1): every generated radius is
                  multiplied by S and every contact-law parameter follows its law's declared rule (value x
                  S^exponent, see "upscaling by S" below); the domain, walls and strain rates stay as given
  contact         (required) particle-particle law: {"law": keyword (default "linear"), parameters...}
  wall_contact    particle-wall law, same form (default: contact); used by the coupling wall
  damping         {"local": 0.7}  local non-viscous damping alpha in [0, 1)
  timestep        {"fraction_of_critical": 0.2} or {"dt_s": s}; dt_s above the critical step is refused
  gravity_m_s2    [gx, gy, gz] (default [0,0,0]); the coupler injects N g
  neighbour       {"skin_m": s} Verlet skin (default 0.2 x the largest radius)
  walls           [ {"type":"plane", "point_m":[..], "normal":[..], "half_size_m" (default: covers the bed),
                     "name", "velocity_m_s":[0,0,0], "start_step":0, "contact":{law} (default wall_contact)},
                    {"type":"facets", "vertices_m":[[x,y,z],...], "facets":[[i,j,k],...], name, velocity_m_s,
                     start_step, contact} ]
  pile            {"radius_m", "tip_z_m", "length_m", "sides":24, "axis_xy_m":[0,0], "velocity_m_s":[0,0,0],
                   "start_step":0, "start_when":{"unbalanced_force_ratio": r} (rest until, at or after start_step,
                   the unbalanced-force ratio is at most r: loading after equilibrium), "ramp_steps":0 (the
                   velocity rises linearly from 0 over this many steps), "contact"}  closed
                  cylinder with a flat tip; monitors pile_force_n, pile_tip_force_n, pile_shaft_force_n,
                  pile_displacement_m. With "wall_thickness_m": t (< radius_m) an open-ended tube (the tip
                  is the annulus) that also sends pile_inner_shaft_force_n, pile_outer_shaft_force_n and
                  the soil column inside it: pile_plug_length_m, pile_plug_particles (pile_plug.hpp)
  ucs             {"top_wall", "bottom_wall" (names of two walls), "area_m2" (default: derived from a lattice
                   bed with platens normal to z: disc through the outermost particle of a cylinder, x-y bounding
                   box of a box), "seat_platens" (true: move both platens along the axis onto the outermost particles),
                   "strain_rate_per_s" (optional: moves each platen at rate H0/2 towards the other;
                   the platens must then have no velocity_m_s), "start_step":0}
                  adds the monitors axial_stress_pa (platen force / area, compression positive, averaged over
                  the advance and over both platens) and axial_strain ((H0 - H)/H0, H the platen separation)
  triaxial        triaxial compression in six rigid plane walls (docs/dem_triaxial_walls.md):
                  {"top_wall", "bottom_wall", "lateral_walls":[first, second of one pair, first, second of the
                   other] (wall names; the three pairs face each other along perpendicular directions),
                   "confining_stress_pa" (sigma_3, required), "strain_rate_per_s" (axial, required: each platen
                   moves at rate H0/2), "seat_walls":true (move every wall onto the outermost particles),
                   "servo":{"gain":0.5, "max_strain_rate_per_s" (cap of a servo-controlled pair; default
                   1e-4 / dt)}, "confinement":{"tolerance":0.01, "unbalanced_force_ratio":0.01,
                   "max_steps":200000, "check_every":100}}
                  preparation: all six walls servo-controlled to sigma_3, then bonds; during advance the
                  platens close and the lateral walls hold sigma_3. The six walls must have no velocity_m_s.
                  Monitors: axial_stress_pa, lateral_stress_pa, deviatoric_stress_pa (averaged over the
                  advance), axial_strain (H0 - H)/H0, volumetric_strain (V0 - V)/V0, porosity (of the box)
  threads         OpenMP threads, 0..1024 (0: OpenMP default)
)" + periodic_config_help() + "Contact-law registry:\n" + describe_contact_laws();
}

}  // namespace dfc::dem
