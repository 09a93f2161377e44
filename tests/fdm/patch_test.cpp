// Patch test: a uniform strain imposed on the boundary of a distorted mesh
// must give a uniform stress equal to the elastic law everywhere (consistency
// of §1.4 strain rates, §1.5 mixed discretization and §1.7 nodal forces).
#include <gtest/gtest.h>

#include <cmath>

#include "dfc/fdm/mesh_generators.hpp"
#include "fdm_test_support.hpp"

namespace dfc::fdm {
namespace {

TEST(PatchTest, UniformBoundaryStrainGivesUniformElasticStressOnDistortedMesh) {
  Mesh mesh = make_box({Vec3::Zero(), Vec3(1.0, 1.2, 0.9), {3, 3, 3}});
  // Move every interior gridpoint by up to ±15 % of a zone so that no zone is a
  // parallelepiped: a correct scheme still reproduces the uniform field.
  const auto on_boundary = [](const Vec3& p, const Vec3& size) {
    for (Eigen::Index c = 0; c < 3; ++c)
      if (std::abs(p[c]) < 1e-12 || std::abs(p[c] - size[c]) < 1e-12) return true;
    return false;
  };
  const Vec3 size(1.0, 1.2, 0.9);
  for (std::size_t gp = 0; gp < mesh.points.size(); ++gp)
    if (!on_boundary(mesh.points[gp], size))
      mesh.points[gp] += 0.05 * Vec3(std::sin(3.0 * double(gp)), std::cos(5.0 * double(gp)), std::sin(7.0 * double(gp) + 1.0));

  const double young = 2.0e7;
  const double poisson = 0.3;
  Solver solver(mesh, test::elastic_material(young, poisson, 2000.0), test::quiet_settings());

  // Target uniform strain (small, with shear), reached in one step by
  // prescribing v = ε·x/Δt on the boundary, then held.
  Eigen::Matrix3d strain;
  strain << 1.0e-4, 2.0e-5, -3.0e-5, 2.0e-5, -5.0e-5, 4.0e-5, -3.0e-5, 4.0e-5, 2.0e-5;
  const double dt = 1.0;
  std::vector<Index> boundary;
  for (std::size_t gp = 0; gp < mesh.points.size(); ++gp)
    if (on_boundary(mesh.points[gp], size)) boundary.push_back(gp);
  for (const Index gp : boundary) solver.prescribe_velocity(gp, strain * mesh.points[gp] / dt);
  solver.step(dt);
  for (const Index gp : boundary) solver.prescribe_velocity(gp, Vec3::Zero());
  ASSERT_GT(test::run_to_equilibrium(solver, dt, 1e-12, 50000), 0);

  // Hooke's law: σ = λ tr(ε) I + 2G ε.
  const double shear = young / (2.0 * (1.0 + poisson));
  const double lame = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  const Eigen::Matrix3d expected = lame * strain.trace() * Eigen::Matrix3d::Identity() + 2.0 * shear * strain;
  const SymTensor expected_stress = SymTensor::symmetric_part(expected);
  const double scale = expected.cwiseAbs().maxCoeff();
  // Converged to ufr < 1e-12: the residual stress error is of that order
  // relative to the stress; 1e-8 is far below any discretization error a
  // failing patch test would show (O(jitter) = O(10 %)).
  double worst = 0.0;
  for (const Stress& s : solver.tetrahedron_stresses())
    for (std::size_t c = 0; c < 6; ++c) worst = std::max(worst, std::abs(s.components()[c] - expected_stress.components()[c]) / scale);
  EXPECT_LT(worst, 1e-8);
  // Interior gridpoints move with the affine field too.
  for (std::size_t gp = 0; gp < mesh.points.size(); ++gp)
    EXPECT_LT((solver.displacements()[gp] - strain * mesh.points[gp]).norm(), 1e-8 * strain.norm()) << "gridpoint " << gp;
}

}  // namespace
}  // namespace dfc::fdm
