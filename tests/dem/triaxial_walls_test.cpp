// Triaxial walls: geometry, stress signs and the wall servo on a case with a
// closed form, and the "triaxial" section's checks.
#include <gtest/gtest.h>

#include <cmath>

#include "dem_test_support.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/dem/dem_config.hpp"
#include "dfc/dem/model_layout.hpp"
#include "dfc/dem/triaxial_walls.hpp"
#include "dfc/dem/wall_builders.hpp"

namespace dfc::dem {
namespace {

constexpr double kRadius = 0.005;  // m
constexpr double kKn = 1e5;        // N/m

/// One sphere of radius R at the origin touching six frictionless walls at ±R.
struct SphereInBox {
  Simulation sim;
  TriaxialWalls box;
};

SphereInBox sphere_in_box() {
  const ContactLawSetting smooth = test::linear(kKn, kKn, 0.0);
  SphereInBox s{Simulation(SimulationSettings{.particle_law = smooth, .gravity = {}, .local_damping = 0.7, .skin = 0.0, .threads = 1}), {}};
  s.sim.add_sphere(0, {0, 0, 0}, kRadius, 2650);
  const auto wall = [&](const char* name, Vec3 point, Vec3 normal) {
    return s.sim.add_wall(make_wall(name, make_plane_mesh(point, normal, 2 * kRadius), WallMotion::prescribed, smooth));
  };
  s.box.top = wall("top", {0, 0, kRadius}, {0, 0, -1});
  s.box.bottom = wall("bottom", {0, 0, -kRadius}, {0, 0, 1});
  s.box.lateral = {wall("x0", {-kRadius, 0, 0}, {1, 0, 0}), wall("x1", {kRadius, 0, 0}, {-1, 0, 0}), wall("y0", {0, -kRadius, 0}, {0, 1, 0}),
                   wall("y1", {0, kRadius, 0}, {0, -1, 0})};
  return s;
}

TEST(TriaxialWalls, AxesSizeAndCompressionPositiveStress) {
  SphereInBox s = sphere_in_box();
  const BoxAxes axes = box_axes(box_vertices(s.sim.walls(), s.box));
  EXPECT_NEAR(axes.axis.z, 1.0, 1e-15);
  EXPECT_NEAR(axes.lateral[0].x, 1.0, 1e-15);
  EXPECT_NEAR(axes.lateral[1].y, 1.0, 1e-15);
  const BoxSize size = box_size(s.sim.walls(), s.box, axes);
  EXPECT_NEAR(size.height, 2 * kRadius, 1e-15);
  EXPECT_NEAR(size.volume(), 8 * kRadius * kRadius * kRadius, 1e-18);
  // Push every wall in by d: the sphere pushes each outwards with kn d, on an
  // area (2R - 2d)^2 once all walls moved: sigma = kn d / (2R - 2d)^2 on all six.
  const double d = 1e-5;
  for (const std::size_t w : s.box.in_order()) s.sim.set_wall_velocity(w, {});
  const BoxStress before = [&] {
    s.sim.step(1e-9);
    return box_stress(s.sim.walls(), s.box, axes, box_size(s.sim.walls(), s.box, axes));
  }();
  EXPECT_EQ(before.axial(), 0.0);  // touching, not pressed
  const std::array<Vec3, 6> inward{Vec3{0, 0, -1}, Vec3{0, 0, 1}, Vec3{1, 0, 0}, Vec3{-1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, -1, 0}};
  const auto order = s.box.in_order();
  for (std::size_t k = 0; k < 6; ++k) s.sim.set_wall_velocity(order[k], (d / 1e-6) * inward[k]);
  s.sim.step(1e-6);  // the walls move after the forces: one more step reads the overlap
  for (const std::size_t w : order) s.sim.set_wall_velocity(w, {});
  s.sim.step(1e-12);
  const BoxSize pressed = box_size(s.sim.walls(), s.box, axes);
  const BoxStress stress = box_stress(s.sim.walls(), s.box, axes, pressed);
  const double expected = kKn * d / ((2 * kRadius - 2 * d) * (2 * kRadius - 2 * d));
  for (const double sigma : stress.wall) EXPECT_NEAR(sigma, expected, 1e-9 * expected);
  EXPECT_NEAR(stress.deviator(), 0.0, 1e-9 * expected);
}

// PFC's servo with the contact's own stiffness: one contact per wall, so
// k_n N_c is the exact stiffness and each step removes the fraction `gain` of
// the error (up to the area change, second order). After 200 steps at gain 0.5
// the error is at round-off; the overlap then solves kn d = sigma (2R - 2d)^2.
TEST(TriaxialWalls, ServoBringsEveryWallToTheConfiningStress) {
  SphereInBox s = sphere_in_box();
  LocalEngine engine(s.sim);
  const BoxAxes axes = box_axes(box_vertices(s.sim.walls(), s.box));
  const double sigma = 2e4;  // Pa
  const TriaxialControl control{.confining_stress = sigma, .gain = 0.5, .max_strain_rate = 1000.0, .platen_speed = std::nullopt};
  const double dt = 1e-6;
  BoxStress stress;
  for (int step = 0; step < 400; ++step) stress = triaxial_step(engine, s.box, axes, control, dt);
  EXPECT_LT(confinement_error(stress, control), 1e-9);
  // kn d = sigma (2R - 2d)^2, the smaller root.
  const double a = 4 * sigma, b = -(8 * sigma * kRadius + kKn), c = 4 * sigma * kRadius * kRadius;
  const double d = (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
  const BoxSize size = box_size(s.sim.walls(), s.box, axes);
  // The walls still creep at the last velocity (error ~1e-9 of sigma): 1e-9 of d.
  EXPECT_NEAR(size.height, 2 * kRadius - 2 * d, 1e-9 * d + 1e-15);
  EXPECT_NEAR(size.width[0], 2 * kRadius - 2 * d, 1e-9 * d + 1e-15);
}

TEST(TriaxialWalls, ShearingMovesThePlatensAtTheirSpeedAndHoldsTheSides) {
  SphereInBox s = sphere_in_box();
  LocalEngine engine(s.sim);
  const BoxAxes axes = box_axes(box_vertices(s.sim.walls(), s.box));
  const double sigma = 2e4, dt = 1e-6;
  TriaxialControl control{.confining_stress = sigma, .gain = 0.5, .max_strain_rate = 1000.0, .platen_speed = std::nullopt};
  for (int step = 0; step < 400; ++step) (void)triaxial_step(engine, s.box, axes, control, dt);
  const BoxSize start = box_size(s.sim.walls(), s.box, axes);
  control.platen_speed = 1e-2;  // m/s
  BoxStress stress;
  const int steps = 2000;
  for (int step = 0; step < steps; ++step) stress = triaxial_step(engine, s.box, axes, control, dt);
  const BoxSize end = box_size(s.sim.walls(), s.box, axes);
  // The platens started at rest (the confinement converged) and moved at
  // 1 cm/s each from the second shearing step on (the first used the
  // confinement's last velocities).
  EXPECT_NEAR(start.height - end.height, 2 * 1e-2 * dt * (steps - 1), 1e-9 * (start.height - end.height));
  // The sphere's overlaps are independent: the platens' overlap is R - H/2 (the
  // sphere stays centred), the sides' the servo's; so sigma_a = kn (R - H/2) / (W0 W1)
  // and each side holds sigma_3 with its area H W shrinking. Measured one step
  // before `end` (the walls move after the forces): tolerance 1e-3, one step of
  // platen travel against the overlap.
  const double overlap = kRadius - 0.5 * (end.height + 2 * 1e-2 * dt);
  EXPECT_NEAR(stress.axial(), kKn * overlap / (end.width[0] * end.width[1]), 1e-3 * stress.axial());
  EXPECT_GT(stress.axial(), 2 * sigma);
  for (std::size_t k = 2; k < 6; ++k) EXPECT_NEAR(stress.wall[k], sigma, 1e-3 * sigma) << "lateral wall " << k;
}

nlohmann::json triaxial_config() {
  nlohmann::json c = test::box_bed_config();
  c.erase("gravity_m_s2");
  c["particles"]["region"] = {{"type", "box"}, {"min_m", {0, 0, 0}}, {"max_m", {0.03, 0.03, 0.06}}};
  const auto plane = [](const char* name, std::array<double, 3> p, std::array<double, 3> n) {
    return nlohmann::json{{"type", "plane"}, {"name", name}, {"point_m", p}, {"normal", n}, {"half_size_m", 0.1}};
  };
  c["walls"] = nlohmann::json::array({plane("bottom", {0.015, 0.015, 0}, {0, 0, 1}), plane("top", {0.015, 0.015, 0.06}, {0, 0, -1}),
                                      plane("x0", {0, 0.015, 0.03}, {1, 0, 0}), plane("x1", {0.03, 0.015, 0.03}, {-1, 0, 0}),
                                      plane("y0", {0.015, 0, 0.03}, {0, 1, 0}), plane("y1", {0.015, 0.03, 0.03}, {0, -1, 0})});
  c["triaxial"] = {{"top_wall", "top"},
                   {"bottom_wall", "bottom"},
                   {"lateral_walls", {"x0", "x1", "y0", "y1"}},
                   {"confining_stress_pa", 1e3},
                   {"strain_rate_per_s", 1.0}};
  return c;
}

std::string config_error_key(const nlohmann::json& c) {
  try {
    (void)parse_dem_config(c);
  } catch (const ConfigError& e) {
    return e.key_path();
  }
  return "(no error)";
}

TEST(TriaxialWalls, SectionIsCheckedWithTheKeyToFix) {
  const nlohmann::json good = triaxial_config();
  const DemConfig parsed = parse_dem_config(good);
  ASSERT_TRUE(parsed.triaxial.has_value());
  // Seated: the top platen now touches the highest sphere.
  double top = -1.0;
  const ModelLayout layout = lay_out_model(parsed);
  for (const auto& sphere : layout.spheres) top = std::max(top, sphere.centre.z + sphere.radius);
  EXPECT_NEAR(layout.walls[1].mesh.vertices[0].z, top, 1e-15);

  nlohmann::json c = good;
  c["triaxial"]["lateral_walls"] = {"x0", "x1", "y0"};
  EXPECT_EQ(config_error_key(c), "triaxial.lateral_walls");
  c = good;
  c["triaxial"]["lateral_walls"] = {"x0", "x1", "y0", "nowhere"};
  EXPECT_EQ(config_error_key(c), "triaxial.lateral_walls");
  c = good;
  c["triaxial"]["lateral_walls"] = {"x0", "x1", "y0", "top"};
  EXPECT_EQ(config_error_key(c), "triaxial.lateral_walls");
  c = good;
  c["walls"][3]["point_m"] = {0.03, 0.015, 0.05};  // x1 no longer faces x0 along x alone
  EXPECT_EQ(config_error_key(c), "triaxial.lateral_walls");
  c = good;
  c["walls"][0]["velocity_m_s"] = {0, 0, 0.1};
  EXPECT_EQ(config_error_key(c), "triaxial.top_wall");
  c = good;
  c["triaxial"].erase("confining_stress_pa");
  EXPECT_EQ(config_error_key(c), "triaxial.confining_stress_pa");
  c = good;
  c["ucs"] = {{"top_wall", "top"}, {"bottom_wall", "bottom"}};
  EXPECT_EQ(config_error_key(c), "triaxial.top_wall");
}

// Radius expansion inside the walls: the spheres are placed in the box the six
// walls bound (whole spheres inside it) and the porosity target refers to it.
TEST(TriaxialWalls, RadiusExpansionFillsTheBoxOfTheWalls) {
  nlohmann::json c = triaxial_config();
  c["particles"] = {{"generator", "radius_expansion"}, {"density_kg_m3", 2650}, {"radius_min_m", 0.002}, {"radius_max_m", 0.0025},
                    {"porosity", 0.5},                 {"seed", 4}};
  const ModelLayout parsed = lay_out_model(parse_dem_config(c));
  ASSERT_FALSE(parsed.spheres.empty());
  double solid = 0.0;
  for (std::size_t k = 0; k < parsed.spheres.size(); ++k) {
    const GeneratedSphere& s = parsed.spheres[k];
    EXPECT_GE(s.centre.x - s.radius, 0.0);
    EXPECT_LE(s.centre.z + s.radius, 0.06);
    const double r = parsed.final_radius[k];
    solid += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  }
  EXPECT_NEAR(1.0 - solid / (0.03 * 0.03 * 0.06), 0.5, 1e-12);
  EXPECT_EQ(parsed.walls[1].mesh.vertices[0].z, 0.06);  // not seated: the walls are the container
  c.erase("triaxial");
  EXPECT_EQ(config_error_key(c), "particles.generator");
}

}  // namespace
}  // namespace dfc::dem
