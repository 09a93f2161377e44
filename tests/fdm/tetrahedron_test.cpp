// Tetrahedron kernels and the two-overlay decomposition (docs/theory/fdm.md §1.2–§1.5, §1.7).
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>

#include "dfc/common/errors.hpp"
#include "dfc/fdm/hex_overlays.hpp"
#include "dfc/fdm/mesh_generators.hpp"
#include "dfc/fdm/mixed_discretization.hpp"
#include "dfc/fdm/tetrahedron.hpp"

namespace dfc::fdm {
namespace {

// Round-off of O(10) flops on O(1) numbers: a few 1e-16; 1e-13 leaves margin
// while any formula error (a wrong sign or factor) shows up at O(1).
constexpr double kRoundOff = 1e-13;

Tetrahedron skewed_tetrahedron() {
  const std::array<Vec3, 4> x = {Vec3(0.1, -0.2, 0.05), Vec3(1.3, 0.1, -0.1), Vec3(0.2, 0.9, 0.3), Vec3(0.4, 0.35, 1.1)};
  return make_tetrahedron({0, 1, 2, 3}, x);
}

std::vector<Vec3> tetrahedron_points() { return {Vec3(0.1, -0.2, 0.05), Vec3(1.3, 0.1, -0.1), Vec3(0.2, 0.9, 0.3), Vec3(0.4, 0.35, 1.1)}; }

Mesh single_zone(const std::function<Vec3(const Vec3&)>& map) {
  Mesh mesh = make_box({});
  for (Vec3& p : mesh.points) p = map(p);
  return mesh;
}

TEST(Tetrahedron, AreaVectorsSumToZeroAndPointOutward) {
  const Tetrahedron tet = skewed_tetrahedron();
  const auto x = tetrahedron_points();
  // §1.3: Σ a⁽ⁿ⁾ = 0 (closed surface).
  Vec3 sum = Vec3::Zero();
  for (const Vec3& a : tet.area) sum += a;
  EXPECT_LT(sum.norm(), kRoundOff);
  // Outward: a⁽ⁿ⁾ points away from node n, towards the face.
  for (std::size_t n = 0; n < 4; ++n) EXPECT_GT(tet.area[n].dot(x[(n + 1) % 4] - x[n]), 0.0);
  // V = |det[x2−x1, x3−x1, x4−x1]|/6 and, by the divergence theorem, V = ⅓ Σ a⁽ⁿ⁾·c⁽ⁿ⁾.
  Eigen::Matrix3d m;
  m << x[1] - x[0], x[2] - x[0], x[3] - x[0];
  EXPECT_NEAR(tet.volume, std::abs(m.determinant()) / 6.0, kRoundOff);
  double divergence_volume = 0.0;
  for (std::size_t n = 0; n < 4; ++n) divergence_volume += tet.area[n].dot((x[(n + 1) % 4] + x[(n + 2) % 4] + x[(n + 3) % 4]) / 3.0) / 3.0;
  EXPECT_NEAR(divergence_volume, tet.volume, kRoundOff);
}

TEST(Tetrahedron, StrainRateRecoversAffineVelocityGradient) {
  const Tetrahedron tet = skewed_tetrahedron();
  Eigen::Matrix3d gradient;
  gradient << 0.3, -1.2, 0.7, 2.1, -0.4, 0.25, -0.6, 0.9, 1.5;
  const Vec3 translation(0.2, -0.1, 0.4);
  std::vector<Vec3> velocity;
  for (const Vec3& x : tetrahedron_points()) velocity.push_back(gradient * x + translation);
  // §1.4: exact for a linear velocity field.
  EXPECT_LT((velocity_gradient(tet, velocity) - gradient).cwiseAbs().maxCoeff(), kRoundOff);
  const SymTensor rate = strain_rate(tet, velocity);
  const SymTensor expected = SymTensor::symmetric_part(gradient);
  for (std::size_t c = 0; c < 6; ++c) EXPECT_NEAR(rate.components()[c], expected.components()[c], kRoundOff);
}

TEST(Tetrahedron, RigidRotationGivesZeroStrainRate) {
  const Tetrahedron tet = skewed_tetrahedron();
  const Vec3 omega(0.7, -1.3, 2.2);
  const Vec3 translation(1.0, 2.0, -0.5);
  std::vector<Vec3> velocity;
  for (const Vec3& x : tetrahedron_points()) velocity.push_back(omega.cross(x) + translation);
  for (const double c : strain_rate(tet, velocity).components()) EXPECT_NEAR(c, 0.0, kRoundOff);
}

TEST(Tetrahedron, NodalForcesBalanceAndDissipateInternalPower) {
  const Tetrahedron tet = skewed_tetrahedron();
  const SymTensor stress{1.5, -2.0, 0.7, 0.3, -0.4, 0.9};
  const auto forces = nodal_forces(tet, stress);
  Vec3 sum = Vec3::Zero();
  for (const Vec3& f : forces) sum += f;
  EXPECT_LT(sum.norm(), kRoundOff);  // a constant stress is self-equilibrated
  // §1.7 check: Σ fⁿ·vⁿ = −V σ:ξ for any velocities.
  const std::vector<Vec3> velocity = {Vec3(0.3, 0.1, -0.2), Vec3(-0.5, 0.4, 0.0), Vec3(0.2, -0.3, 0.6), Vec3(0.1, 0.2, 0.3)};
  double power = 0.0;
  for (std::size_t n = 0; n < 4; ++n) power += forces[n].dot(velocity[n]);
  const SymTensor rate = strain_rate(tet, velocity);
  const double contraction = stress.xx * rate.xx + stress.yy * rate.yy + stress.zz * rate.zz +
                             2.0 * (stress.xy * rate.xy + stress.yz * rate.yz + stress.zx * rate.zx);
  EXPECT_NEAR(power, -tet.volume * contraction, kRoundOff);
}

TEST(HexOverlays, EachOverlayFillsAParallelepiped) {
  Eigen::Matrix3d map;
  map << 1.2, 0.3, -0.1, 0.2, 0.9, 0.25, 0.1, -0.2, 1.4;
  const Mesh mesh = single_zone([&](const Vec3& p) { return Vec3(map * p); });
  const auto tets = zone_tetrahedra(mesh, 0);
  double overlay_a = 0.0;
  double overlay_b = 0.0;
  for (std::size_t t = 0; t < kTetrahedraPerZone; ++t) {
    EXPECT_GT(tets[t].volume, 0.0) << "tetrahedron " << t;  // the table is positively oriented (§1.2)
    (t < 5 ? overlay_a : overlay_b) += tets[t].volume;
  }
  EXPECT_NEAR(overlay_a, map.determinant(), kRoundOff);
  EXPECT_NEAR(overlay_b, map.determinant(), kRoundOff);
}

TEST(HexOverlays, EachOverlayFillsAFrustum) {
  // Square frustum: base side 2, top side 1, height 1.5 (planar faces, not a
  // parallelepiped). V = h/3 (A₁ + A₂ + √(A₁A₂)).
  const Mesh mesh = single_zone([](const Vec3& p) {
    const double side = 2.0 - p.z();
    return Vec3((p.x() - 0.5) * side, (p.y() - 0.5) * side, 1.5 * p.z());
  });
  const double expected = 1.5 / 3.0 * (4.0 + 1.0 + 2.0);
  const auto tets = zone_tetrahedra(mesh, 0);
  double overlay_a = 0.0;
  double overlay_b = 0.0;
  for (std::size_t t = 0; t < kTetrahedraPerZone; ++t) (t < 5 ? overlay_a : overlay_b) += tets[t].volume;
  EXPECT_NEAR(overlay_a, expected, kRoundOff);
  EXPECT_NEAR(overlay_b, expected, kRoundOff);
}

TEST(HexOverlays, EveryCornerBelongsToFiveTetrahedra) {
  std::array<int, 8> count{};
  for (const auto& tet : kOverlayTetrahedra)
    for (const int corner : tet) ++count[std::size_t(corner)];
  for (const int c : count) EXPECT_EQ(c, 5);  // §1.2 derived check
}

TEST(HexOverlays, InvertedZoneIsRejectedByName) {
  Mesh mesh = make_box({Vec3::Zero(), Vec3::Ones(), {2, 1, 1}});
  std::swap(mesh.zones[1][0], mesh.zones[1][1]);  // corners out of order: mirrored zone
  try {
    check_mesh_quality(mesh);
    FAIL() << "an inverted zone was accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("zones 1"), std::string::npos) << e.what();
  }
}

TEST(MixedDiscretization, ReplacesTraceByVolumeAverageAndKeepsDeviator) {
  std::array<SymTensor, 2> rates = {SymTensor{1.0, 2.0, 3.0, 0.5, 0.0, 0.0}, SymTensor{-1.0, 0.0, 0.0, 0.0, 0.2, 0.0}};
  const std::array<double, 2> volumes = {1.0, 3.0};
  const std::array<SymTensor, 2> before = rates;
  apply_mixed_discretization(rates, volumes);
  const double average = (6.0 * 1.0 + (-1.0) * 3.0) / 4.0;  // §1.5
  for (std::size_t t = 0; t < 2; ++t) {
    EXPECT_NEAR(rates[t].trace(), average, kRoundOff);
    const auto d0 = before[t].deviator().components();
    const auto d1 = rates[t].deviator().components();
    for (std::size_t c = 0; c < 6; ++c) EXPECT_NEAR(d1[c], d0[c], kRoundOff);
  }
}

}  // namespace
}  // namespace dfc::fdm
