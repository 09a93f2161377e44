// Stored in-plane vectors turning with the contact plane
// (contact_plane_rotation.hpp): the frame rotation used by laws that keep the
// previous normal (linear_pbond) and the twirl about the normal, checked
// against Rodrigues' formula written out independently, and the invariants
// any rotation of the contact frame must keep (length, the new plane, the
// direction along the rotation axis).
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

#include "dfc/dem/contact_plane_rotation.hpp"

namespace dfc::dem {
namespace {

/// Two stored vectors and the previous normal, as a law that declares them.
struct FrameHistoryLaw {
  static constexpr std::array<std::size_t, 2> in_plane_history{0, 3};
  static constexpr std::size_t previous_normal_offset = 6;
};

/// Rodrigues' rotation of v about the unit axis k by angle theta:
/// v cos θ + (k × v) sin θ + k (k·v)(1 − cos θ).
Vec3 rodrigues(const Vec3& v, const Vec3& k, double theta) {
  return std::cos(theta) * v + std::sin(theta) * cross(k, v) + (dot(k, v) * (1.0 - std::cos(theta))) * k;
}

Vec3 unit(const Vec3& v) { return (1.0 / norm(v)) * v; }

// Round-off bound: each formula is a handful of operations on O(1) numbers,
// so 1e-14 (about 50 ulp) is far below any error of the formula itself (the
// first-order projection misses by ~θ², 0.25 at the 60° used here).
constexpr double round_off = 1e-14;

TEST(ContactFrameRotation, IsRodriguesRotationFromThePreviousToTheCurrentNormal) {
  const Vec3 n0 = unit({1.0, 0.2, -0.3});
  // n1: n0 turned by 60° about an axis perpendicular to it.
  const Vec3 axis = unit(cross(n0, Vec3{0.1, 1.0, 0.4}));
  const double theta = std::numbers::pi / 3.0;
  const Vec3 n1 = rodrigues(n0, axis, theta);
  // Two vectors in the old plane: one across the axis, one mixed.
  const Vec3 a = 3.0 * cross(axis, n0);
  const Vec3 b = 0.5 * axis + 2.0 * cross(axis, n0);
  double history[9] = {a.x, a.y, a.z, b.x, b.y, b.z, n0.x, n0.y, n0.z};
  ContactKinematics k;  // no spin: the tilt alone
  k.normal = n1;
  rotate_in_plane_history<FrameHistoryLaw>(history, k);
  const Vec3 ra = load_vec3(history);
  const Vec3 rb = load_vec3(history + 3);
  EXPECT_LT(norm(ra - rodrigues(a, axis, theta)), round_off * norm(a));
  EXPECT_LT(norm(rb - rodrigues(b, axis, theta)), round_off * norm(b));
  // The new normal is stored for the next step.
  EXPECT_EQ(load_vec3(history + 6).x, n1.x);
  EXPECT_EQ(load_vec3(history + 6).y, n1.y);
  EXPECT_EQ(load_vec3(history + 6).z, n1.z);
  // Project-and-rescale differs from the rotation at this angle (the test can tell them apart).
  EXPECT_GT(norm(rotate_into_contact_plane(b, n1) - rodrigues(b, axis, theta)), 0.1 * norm(b));
}

TEST(ContactFrameRotation, KeepsLengthPutsVectorsInTheNewPlaneAndAgreesWithProjectionToFirstOrder) {
  const Vec3 n0 = unit({-0.3, 0.9, 0.1});
  const Vec3 v = 2.5 * unit(cross(n0, Vec3{1.0, 0.0, 0.0})) + 0.7 * unit(cross(n0, Vec3{0.0, 0.0, 1.0}));
  for (const double theta : {1e-6, 1e-3, 0.1, 1.0, 2.5}) {
    const Vec3 axis = unit(cross(n0, Vec3{0.3, 0.2, 1.0}));
    const Vec3 n1 = rodrigues(n0, axis, theta);
    const Vec3 turned = ContactFrameRotation::between(n0, n1).apply(v);
    EXPECT_NEAR(norm(turned), norm(v), round_off * norm(v)) << theta;
    EXPECT_LT(std::abs(dot(turned, n1)), round_off * norm(v)) << theta;
    // Both conventions turn a vector with the plane; they differ at second order only.
    const double difference = norm(turned - rotate_into_contact_plane(v, n1));
    EXPECT_LT(difference, (theta * theta + round_off) * norm(v)) << theta;
  }
}

// The twirl turns an in-plane vector about the normal by 2 atan(theta/2),
// theta = mean spin about the normal x dt, checked against Rodrigues' formula
// (round-off tolerance as above), and with no spin it gives v back bit for bit.
TEST(ContactTwirl, TurnsAboutTheNormalByTheMeanSpinAndIsTheIdentityWithoutSpin) {
  const Vec3 n = unit({0.2, -0.5, 0.8});
  const Vec3 v = 1.5 * unit(cross(n, Vec3{1.0, 0.0, 0.0}));
  ContactKinematics k;
  k.normal = n;
  k.dt = 1e-3;
  for (const double spin : {-300.0, 1e-3, 2.0, 40.0}) {
    k.mean_spin_about_normal = spin;
    const double theta = spin * k.dt;
    const Vec3 turned = ContactTwirl::of(k).apply(v, n);
    EXPECT_LT(norm(turned - rodrigues(v, n, 2.0 * std::atan(0.5 * theta))), round_off * norm(v)) << spin;
    // and within theta³/12 of the exact angle theta
    EXPECT_LT(norm(turned - rodrigues(v, n, theta)), (std::abs(theta * theta * theta) / 12.0 * 1.01 + round_off) * norm(v)) << spin;
  }
  k.mean_spin_about_normal = 0.0;
  const Vec3 same = ContactTwirl::of(k).apply(v, n);
  EXPECT_EQ(same.x, v.x);
  EXPECT_EQ(same.y, v.y);
  EXPECT_EQ(same.z, v.z);
}

TEST(ContactFrameRotation, FirstContactProjectsAndOppositeNormalsDoNotDivideByZero) {
  const Vec3 n1{0.0, 0.0, 1.0};
  const Vec3 v{1.0, 2.0, 3.0};
  // No previous normal stored: the plain projection onto the new plane.
  const Vec3 fresh = ContactFrameRotation::between(Vec3{}, n1).apply(v);
  EXPECT_EQ(fresh.x, 1.0);
  EXPECT_EQ(fresh.y, 2.0);
  EXPECT_EQ(fresh.z, 0.0);
  const Vec3 flipped = ContactFrameRotation::between(-1.0 * n1, n1).apply(v);
  EXPECT_TRUE(std::isfinite(flipped.x) && std::isfinite(flipped.y) && std::isfinite(flipped.z));
  EXPECT_EQ(flipped.z, 0.0);
}

/// The three doubles' bits, so that +0 and -0 differ.
std::array<std::uint64_t, 3> bits(const Vec3& v) { return {std::bit_cast<std::uint64_t>(v.x), std::bit_cast<std::uint64_t>(v.y), std::bit_cast<std::uint64_t>(v.z)}; }

/// A law without a previous normal: each vector projected, rescaled and twirled.
struct ProjectingLaw {
  static constexpr std::array<std::size_t, 2> in_plane_history{0, 3};
};

// rotate_in_plane_history leaves a +0 vector as it is (no store) because
// turning it gives +0 bit for bit at any normal and any spin below a quarter
// turn per step; and every other vector, -0 included, exactly as
// turn_with_contact_plane turns it.
TEST(ContactTwirl, APositiveZeroVectorTurnsIntoPositiveZeroAndTheSkipChangesNoBit) {
  std::mt19937_64 rng(46);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::array<std::uint64_t, 3> zero_bits{0, 0, 0};
  for (int trial = 0; trial < 20000; ++trial) {
    ContactKinematics k;
    k.normal = unit({u(rng), u(rng), u(rng)});
    // Spins up to 0.9 of the quarter turn per step (t = spin dt / 2 < 1), and none.
    k.dt = 1e-6;
    k.mean_spin_about_normal = trial % 10 == 0 ? 0.0 : 1.8e6 * u(rng);
    const ContactTwirl twirl = ContactTwirl::of(k);
    ASSERT_GT(twirl.cos_angle, 0.0);
    EXPECT_EQ(bits(turn_with_contact_plane(Vec3{}, k.normal, twirl)), zero_bits) << "trial " << trial;
    // A row with a +0 vector, and one with a vector holding a -0 component.
    std::array<double, 6> row{0.0, 0.0, 0.0, -0.0, 1e-3 * u(rng), 1e-3 * u(rng)};
    const Vec3 second = load_vec3(row.data() + 3);
    rotate_in_plane_history<ProjectingLaw>(row.data(), k);
    EXPECT_EQ(bits(load_vec3(row.data())), zero_bits);
    EXPECT_EQ(bits(load_vec3(row.data() + 3)), bits(turn_with_contact_plane(second, k.normal, twirl)));
  }
}

}  // namespace
}  // namespace dfc::dem
