// The interface condensation of the static elastic reference continuum
// (reference_servers/condensed_elastic_continuum): against a full solve of the
// same system, Maxwell–Betti symmetry, the in-situ state, and the explicit
// FDM's own static limit.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseLU>

#include "dfc/fdm/equilibrium.hpp"
#include "dfc/fdm/fdm_config.hpp"
#include "dfc/reference/condensed_elastic_continuum.hpp"
#include "dfc/reference/elastic_stiffness.hpp"
#include "dfc/reference/free_displacement_basis.hpp"
#include "reference_test_support.hpp"

namespace dfc::reference {
namespace {

using fdm::Index;
using fdm::Vec3;

struct PileContinuum {
  fdm::FdmModel model = fdm::load_fdm_model(test::pile_continuum_section());
  std::vector<Index> interface = model.solver.mesh().face_group_gridpoints("inner");
  CondensedElasticContinuum condensed{model.solver, interface};
};

/// Interface loads of the size the DEM applies: ±1 N per component.
std::vector<double> random_interface_force(std::size_t rows, std::mt19937& generator) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> force(3 * rows);
  for (double& f : force) f = uniform(generator);
  return force;
}

// (a) u_I = C f + u⁰ against an independent solve of the whole constrained
// system Tᵀ K T q = Tᵀ (r₀ + E f) with a different factorization (sparse LU).
// Both are direct solves of the same SPD system in double precision; their
// difference is bounded by ~cond(K)·ε. With ~10 zones through the wall and a
// stiffness ratio of a few between zones, cond(TᵀKT) is ~10⁵, so 1e-9 of the
// displacement norm is a safe bound that any wrong row, column, sign or
// missing r₀ term (errors of order 1) would exceed by many orders.
TEST(CondensedElasticContinuum, CompliancePredictsTheFullSolveForRandomInterfaceLoads) {
  const PileContinuum pile;
  const fdm::Solver& solver = pile.model.solver;
  const std::size_t n_gp = solver.mesh().gridpoint_count();
  const Eigen::SparseMatrix<double> stiffness = assemble_elastic_stiffness(solver.tetrahedra(), n_gp, solver.model().stiffest_moduli());
  const Eigen::SparseMatrix<double> basis = free_displacement_basis(solver);
  const Eigen::SparseMatrix<double> reduced = basis.transpose() * stiffness * basis;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(reduced);
  ASSERT_EQ(lu.info(), Eigen::Success);

  std::mt19937 generator(20240611);
  double worst = 0.0;
  for (int trial = 0; trial < 5; ++trial) {
    const std::vector<double> force = random_interface_force(pile.interface.size(), generator);
    Eigen::VectorXd load(Eigen::Index(3 * n_gp));
    for (Index gp = 0; gp < n_gp; ++gp) load.segment<3>(Eigen::Index(3 * gp)) = solver.force_exerted_on_gridpoint(gp);
    for (std::size_t r = 0; r < pile.interface.size(); ++r)
      for (int c = 0; c < 3; ++c) load[Eigen::Index(3 * pile.interface[r]) + c] += force[3 * r + std::size_t(c)];
    const Eigen::VectorXd full = basis * lu.solve(Eigen::VectorXd(basis.transpose() * load));
    Eigen::VectorXd full_interface(Eigen::Index(3 * pile.interface.size()));
    for (std::size_t r = 0; r < pile.interface.size(); ++r)
      full_interface.segment<3>(Eigen::Index(3 * r)) = full.segment<3>(Eigen::Index(3 * pile.interface[r]));
    const Eigen::VectorXd condensed = pile.condensed.interface_displacement(force);
    worst = std::max(worst, (condensed - full_interface).norm() / full_interface.norm());
  }
  std::printf("[ condensed vs full solve ] worst relative difference %.2e over 5 random loads\n", worst);
  EXPECT_LT(worst, 1e-9);
}

// (c) Maxwell–Betti: the work of load set 1 on the displacements of load set 2
// equals that of 2 on 1, i.e. C = Cᵀ. C is computed column by column without
// symmetrization, so this checks the assembly (K = Kᵀ needs the B-bar volumetric
// term built as w wᵀ) and the condensation. The tolerance is the round-off of
// the solves, ~cond·ε ≈ 1e-11 of the largest entry; an asymmetric stiffness
// term (e.g. λ g_n g_mᵀ instead of g_m g_nᵀ) gives differences of order 0.1.
// C must also be positive definite: loads do positive work.
TEST(CondensedElasticContinuum, ComplianceIsSymmetricAndPositiveDefinite) {
  const PileContinuum pile;
  const Eigen::MatrixXd& compliance = pile.condensed.compliance();
  const double scale = compliance.cwiseAbs().maxCoeff();
  const double asymmetry = (compliance - compliance.transpose()).cwiseAbs().maxCoeff() / scale;
  std::printf("[ Maxwell-Betti ] max |C - C^T| / max |C| = %.2e (C is %ld x %ld)\n", asymmetry, long(compliance.rows()),
              long(compliance.cols()));
  EXPECT_LT(asymmetry, 1e-10);
  std::mt19937 generator(7);
  for (int trial = 0; trial < 5; ++trial) {
    const std::vector<double> f1 = random_interface_force(pile.interface.size(), generator);
    const std::vector<double> f2 = random_interface_force(pile.interface.size(), generator);
    const Eigen::Map<const Eigen::VectorXd> a(f1.data(), Eigen::Index(f1.size()));
    const Eigen::Map<const Eigen::VectorXd> b(f2.data(), Eigen::Index(f2.size()));
    EXPECT_NEAR(a.dot(compliance * b), b.dot(compliance * a), 1e-10 * std::abs(a.dot(compliance * a)));
  }
  // Interface nodes on the fixed bottom ring have zero rows; the others load positively.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 * (compliance + compliance.transpose()));
  EXPECT_GT(eigen.eigenvalues().minCoeff(), -1e-12 * scale);
  EXPECT_GT(eigen.eigenvalues().maxCoeff(), 0.0);
}

// In-situ consistency: DEM forces equal to the geostatic traction on the cavity
// wall (the force the continuum exerts on the interface gridpoints in its
// initial state, negated) hold the wall exactly where it is; with no force the
// unsupported wall converges into the cavity. "Exactly" is round-off: the
// geostatic zone stresses balance gravity in the interior (docs/theory/fdm.md §2(c)),
// so the remaining load is ~1e-12 of the wall load.
TEST(CondensedElasticContinuum, InSituTractionHoldsTheWallStill) {
  const PileContinuum pile;
  const fdm::Solver& solver = pile.model.solver;
  std::vector<double> in_situ(3 * pile.interface.size());
  for (std::size_t r = 0; r < pile.interface.size(); ++r)
    for (int c = 0; c < 3; ++c) in_situ[3 * r + std::size_t(c)] = -solver.force_exerted_on_gridpoint(pile.interface[r])[c];
  const Eigen::VectorXd held = pile.condensed.interface_displacement(in_situ);
  const Eigen::VectorXd& free = pile.condensed.in_situ_displacement();
  std::printf("[ in-situ ] |u| with in-situ traction %.2e m, without %.2e m\n", held.norm(), free.norm());
  EXPECT_LT(held.norm(), 1e-9 * free.norm());
  // Without support, a wall gridpoint at mid-depth moves towards the axis.
  for (std::size_t r = 0; r < pile.interface.size(); ++r) {
    const Vec3& x = solver.mesh().points[pile.interface[r]];
    if (std::abs(x.z() - 0.036) > 1e-9) continue;
    const Vec3 radial = Vec3(x.x(), x.y(), 0.0).normalized();
    EXPECT_LT(free.segment<3>(Eigen::Index(3 * r)).dot(radial), 0.0) << "interface row " << r;
  }
}

// The reference is the static limit of fdm_server's own equations: the
// explicit solver, relaxed to equilibrium under the same interface forces,
// reaches the same interface displacements. Relaxed to an unbalanced-force
// ratio of 1e-9, the explicit solution is within ~1e-5 of its limit (the
// residual over the lowest stiffness); a stiffness that is not the FDM's
// (another tetrahedron split, no mixed discretization) differs by percent.
TEST(CondensedElasticContinuum, MatchesTheExplicitSolverAtEquilibrium) {
  const PileContinuum pile;
  fdm::FdmModel explicit_model = fdm::load_fdm_model(test::pile_continuum_section());
  fdm::Solver& solver = explicit_model.solver;
  std::mt19937 generator(3);
  std::vector<double> force = random_interface_force(pile.interface.size(), generator);
  for (std::size_t r = 0; r < pile.interface.size(); ++r) {
    // In-situ traction plus a random ±1 N, so that the wall stays near its place.
    const Vec3 in_situ = -solver.force_exerted_on_gridpoint(pile.interface[r]);
    for (int c = 0; c < 3; ++c) force[3 * r + std::size_t(c)] += in_situ[c];
    solver.set_external_force(pile.interface[r], Vec3(force[3 * r], force[3 * r + 1], force[3 * r + 2]));
  }
  const int steps = fdm::step_to_equilibrium(solver, fdm::EquilibriumSettings{1.0, 1e-9, 10, 200000});
  ASSERT_GT(steps, 0) << "the explicit solver did not reach equilibrium";
  const Eigen::VectorXd implicit = pile.condensed.interface_displacement(force);
  Eigen::VectorXd relaxed(implicit.size());
  for (std::size_t r = 0; r < pile.interface.size(); ++r) relaxed.segment<3>(Eigen::Index(3 * r)) = solver.displacements()[pile.interface[r]];
  const double difference = (implicit - relaxed).norm() / implicit.norm();
  std::printf("[ implicit vs explicit ] %d explicit steps; relative interface difference %.2e\n", steps, difference);
  EXPECT_LT(difference, 1e-4);
}

}  // namespace
}  // namespace dfc::reference
