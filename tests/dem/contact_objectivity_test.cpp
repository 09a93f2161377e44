// Objectivity of every contact law: a pair carried by a rigid rotation (no
// relative motion at the contact, both bodies spinning at the same omega)
// must carry its stored loads with it, turned by the same rotation and
// unchanged in size. The rotation axis is oblique to the contact normal, so
// the contact plane both tilts (the normal moves) and twirls (turns about the
// normal by omega·n dt each step; contact_plane_rotation.hpp ContactTwirl).
// Without the twirl the stored shear force and bending moment would stay
// behind by the whole spin about the normal (tens of degrees here), so each
// check below fails by O(1) without it. The last test checks the same turn
// at a wall contact, where only the sphere spins.
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/dem/contact_law_registry.hpp"
#include "dfc/dem/wall_builders.hpp"

namespace dfc::dem {
namespace {

constexpr double radius = 1e-3;  // m, both spheres
constexpr double dt = 1e-6;      // s

Vec3 unit(const Vec3& v) { return (1.0 / norm(v)) * v; }

/// Rodrigues' rotation of v about the unit axis a by angle theta.
Vec3 rotate(const Vec3& v, const Vec3& a, double theta) {
  return std::cos(theta) * v + std::sin(theta) * cross(a, v) + (dot(a, v) * (1.0 - std::cos(theta))) * a;
}

ContactKinematics at_rest(const Vec3& normal) {
  ContactKinematics k;
  k.normal = normal;
  k.overlap = 1e-8;  // touching: the frictional part (where the law has one) holds a shear force too
  k.effective_mass = 1e-5;
  k.radius_first = k.radius_second = radius;
  k.dt = dt;
  return k;
}

struct Loads {
  Vec3 force;
  Vec3 couple;
};

/// Loads the contact by one step of relative sliding, opening, bending and
/// twist at normal n0, then carries the pair through a quarter turn about
/// `axis` in `steps` rigid steps. Returns the loads after one step at rest
/// (before the turn) and after the turn.
template <class Law>
std::pair<Loads, Loads> loads_before_and_after_rigid_turn(const nlohmann::json& parameters, const Vec3& n0, const Vec3& axis, int steps) {
  const Law law = std::get<Law>(make_contact_law(parameters).law);
  std::vector<double> history(Law::history_size, 0.0);
  if constexpr (Law::bonded) set_bond_state(history.data(), BondState::intact);
  // Loading: every relative motion at once, small enough to stay elastic and stuck.
  ContactKinematics k = at_rest(n0);
  const Vec3 t1 = unit(cross(n0, Vec3{0.0, 0.0, 1.0}));
  const Vec3 t2 = cross(n0, t1);
  k.relative_velocity = 1e-2 * t1 + 4e-3 * t2 + 2e-4 * n0;
  k.relative_angular_velocity = 0.5 * t2 + 0.3 * n0;
  (void)law.evaluate(k, history.data());
  // At rest: the stored loads alone.
  k = at_rest(n0);
  ContactForce f = law.evaluate(k, history.data());
  const Loads before{f.on_first, f.couple_on_first};
  // The rigid turn: both bodies spin at omega = (angle/step)/dt about `axis`.
  const double step_angle = 0.5 * std::numbers::pi / steps;
  const Vec3 omega = (step_angle / dt) * axis;
  for (int s = 1; s <= steps; ++s) {
    k = at_rest(rotate(n0, axis, s * step_angle));
    k.mean_spin_about_normal = mean_spin_about_normal(omega, omega, k.normal);
    f = law.evaluate(k, history.data());
    if constexpr (Law::bonded) {
      EXPECT_EQ(bond_state(history.data()), BondState::intact) << "step " << s;
    }
  }
  return {before, {f.on_first, f.couple_on_first}};
}

// The normal n0 and an axis at 45° to it: the quarter turn twirls the plane
// by about 64° (pi/2 cos 45°) while it tilts it by as much.
const Vec3 n0 = unit({1.0, 0.2, -0.3});
const Vec3 axis = unit(n0 + unit(cross(n0, Vec3{0.1, 1.0, 0.4})));

/// Tolerances. The twirl of each step turns by 2 atan(theta/2) instead of the
/// exact twist angle 2 atan(tan(phi/2) a·n) of a step phi about a: they differ
/// by O(phi³), 4e-14 rad a step here, 1e-9 over the turn. The tilt is exact
/// for a law that keeps the previous normal (ContactFrameRotation), so there
/// 1e-6 of the load's size bounds the error. Projection and rescale tilts a
/// vector that is not along the tilt by an angle off by O(alpha²) a step
/// (alpha = phi sin 45° = 5.6e-5 rad), which adds up to at most N alpha² =
/// 6e-5 rad over the turn: 1e-4 there. Without the twirl the error is the
/// whole spin about the normal, 64°; `shear_share` below keeps the turned
/// in-plane part of each load at least 1 % of its size, so even then the
/// check fails by 100 times its tolerance.
constexpr int steps = 20000;
constexpr double frame_tolerance = 1e-6;
constexpr double projection_tolerance = 1e-4;

double shear_share(const Vec3& load) { return norm(load - dot(load, n0) * n0) / norm(load); }

void expect_turned(const Vec3& after, const Vec3& before, double tolerance, const char* what) {
  const Vec3 expected = rotate(before, axis, 0.5 * std::numbers::pi);
  ASSERT_GT(shear_share(before), 0.01) << what;
  EXPECT_LT(norm(after - expected), tolerance * norm(before)) << what << ": got (" << after.x << ", " << after.y << ", " << after.z
                                                              << "), expected (" << expected.x << ", " << expected.y << ", " << expected.z << ")";
}

TEST(ContactObjectivity, LinearShearForceTurnsWithARigidlyRotatingPair) {
  const auto [before, after] = loads_before_and_after_rigid_turn<LinearLaw>({{"law", "linear"}, {"kn_n_m", 2e5}, {"ks_n_m", 4e4}}, n0, axis, steps);
  expect_turned(after.force, before.force, projection_tolerance, "force");
}

TEST(ContactObjectivity, LinearPbondLoadsTurnWithARigidlyRotatingPair) {
  const auto [before, after] = loads_before_and_after_rigid_turn<LinearPbondLaw>(
      {{"law", "linear_pbond"}, {"emod_pa", 1e8}, {"pb_emod_pa", 1e8}, {"pb_ten_pa", 1e12}, {"pb_coh_pa", 1e12}}, n0, axis, steps);
  expect_turned(after.force, before.force, frame_tolerance, "force");
  expect_turned(after.couple, before.couple, frame_tolerance, "couple");
}

TEST(ContactObjectivity, SoftBondLoadsTurnWithARigidlyRotatingPair) {
  const auto [before, after] = loads_before_and_after_rigid_turn<SoftBondLaw>(
      {{"law", "soft_bond"}, {"sb_emod_pa", 1e8}, {"sb_ten_pa", 1e12}, {"sb_coh_pa", 1e12}}, n0, axis, steps);
  expect_turned(after.force, before.force, projection_tolerance, "force");
  expect_turned(after.couple, before.couple, projection_tolerance, "couple");
}

TEST(ContactObjectivity, DamageBondLoadsTurnWithARigidlyRotatingPair) {
  const auto [before, after] = loads_before_and_after_rigid_turn<DamageBondLaw>(
      {{"law", "damage_bond"}, {"emod_pa", 1e8}, {"bond_emod_pa", 1e8}, {"ten_pa", 1e12}, {"com_pa", 1e12}, {"coh_pa", 1e12},
       {"ucn_m", 1.0}, {"ucs_m", 1.0}, {"theta_c_rad", 1.0}},
      n0, axis, steps);
  expect_turned(after.force, before.force, projection_tolerance, "force");
  expect_turned(after.couple, before.couple, projection_tolerance, "couple");
}

// A wall does not spin, so a wall contact's plane twirls with half the
// sphere's spin about the normal: the mean of the two bodies' spins
// (contact_kernels.hpp evaluate_wall_contacts). A sphere pressed on a floor
// and spinning about the vertical does not slide (its contact point is on the
// spin axis), so the shear force it stored only turns: by 2 atan(omega dt/4)
// a step (ContactTwirl with theta = omega dt/2), half the sphere's own turn,
// in the same sense. Without the twirl at walls the force would not turn at
// all; with the sphere's whole spin it would turn twice as far: either misses
// by 0.5 rad here.
TEST(ContactObjectivity, WallContactShearForceTurnsWithHalfTheSpheresSpin) {
  constexpr double r = 1e-3, kn = 1e5, overlap = 1e-6, step = 1e-4, omega = 10.0;
  constexpr int spin_steps = 1000;  // omega t / 2 = 0.5 rad
  // So heavy (4e6 kg, I = 1.7 kg m^2) that the contact's 0.1 N and 1e-2 N
  // move it by 1e-16 m a step; its velocities are set again before each step.
  constexpr double density = 1e15;
  const ContactLawSetting law = test::linear(kn, kn, 0.5);
  Simulation sim = test::undamped(law);
  sim.add_wall(make_wall("floor", make_plane_mesh({0, 0, 0}, {0, 0, 1}, 0.05), WallMotion::prescribed, law));
  // Inside one facet of the floor, away from the diagonal its two triangles share.
  sim.add_sphere(0, {0.01, 0.004, r - overlap}, r, density);
  // One step of sliding along x stores a shear force k_s v dt = 1e-2 N (below mu F_n = 0.05 N).
  sim.particles_for_edit().velocity[0] = {1e-3, 0.0, 0.0};
  sim.step(step);
  const Vec3 before = sim.particles().force[0];
  ASSERT_GT(std::hypot(before.x, before.y), 1e-3);
  for (int s = 0; s < spin_steps; ++s) {
    sim.particles_for_edit().velocity[0] = {};
    sim.particles_for_edit().angular_velocity[0] = {0.0, 0.0, omega};
    sim.step(step);
  }
  const Vec3 after = sim.particles().force[0];
  const double angle = spin_steps * 2.0 * std::atan(0.25 * omega * step);
  const Vec3 expected = rotate(Vec3{before.x, before.y, 0.0}, {0.0, 0.0, 1.0}, angle);
  // The normal stays -z exactly (no tilt), and nothing slides: only the
  // rounding of 1000 rotations (~1e-13 relative) separates the two.
  const double shear = std::hypot(before.x, before.y);
  EXPECT_NEAR(after.x, expected.x, 1e-9 * shear);
  EXPECT_NEAR(after.y, expected.y, 1e-9 * shear);
}

}  // namespace
}  // namespace dfc::dem
