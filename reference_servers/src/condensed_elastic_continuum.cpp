#include "dfc/reference/condensed_elastic_continuum.hpp"

#include <algorithm>
#include <string>

#include "dfc/common/errors.hpp"
#include "dfc/reference/elastic_stiffness.hpp"
#include "dfc/reference/free_displacement_basis.hpp"

namespace dfc::reference {

using fdm::Index;
using fdm::Vec3;

namespace {

// LDLᵀ pivots below this fraction of the largest one mean the constrained
// stiffness is singular to double precision: a free rigid-body mode (a
// well-supported mesh has pivots within ~1e-8 of each other or better).
constexpr double kSingularPivotRatio = 1e-12;

}  // namespace

CondensedElasticContinuum::CondensedElasticContinuum(const fdm::Solver& solver, std::vector<Index> interface_gridpoints)
    : interface_gridpoints_(std::move(interface_gridpoints)) {
  const std::size_t n_gp = solver.mesh().gridpoint_count();
  const Eigen::SparseMatrix<double> stiffness = assemble_elastic_stiffness(solver.tetrahedra(), n_gp, solver.model().stiffest_moduli());
  basis_ = free_displacement_basis(solver);
  const Eigen::SparseMatrix<double> reduced_stiffness = Eigen::SparseMatrix<double>(basis_.transpose() * stiffness * basis_);

  factorization_.compute(reduced_stiffness);
  const Eigen::VectorXd pivots = factorization_.vectorD();
  if (factorization_.info() != Eigen::Success || pivots.size() == 0 ||
      pivots.minCoeff() <= kSingularPivotRatio * pivots.cwiseAbs().maxCoeff())
    throw UserError(
        "the elastic reference continuum is not supported against rigid-body motion (singular stiffness); add fixed or roller "
        "boundaries that hold every translation and rotation (rollers alone on a full cylinder leave the rotation about its "
        "axis free: fix one group or cut a sector with theta_min/theta_max rollers)");

  // E: interface row r, component c ↔ degree of freedom 3·gp + c.
  const auto n_interface = Eigen::Index(3 * interface_gridpoints_.size());
  Eigen::SparseMatrix<double> selection(Eigen::Index(3 * n_gp), n_interface);
  std::vector<Eigen::Triplet<double>> ones;
  for (std::size_t r = 0; r < interface_gridpoints_.size(); ++r)
    for (int c = 0; c < 3; ++c) ones.emplace_back(int(3 * interface_gridpoints_[r]) + c, int(3 * r) + c, 1.0);
  selection.setFromTriplets(ones.begin(), ones.end());
  interface_basis_ = basis_.transpose() * selection;

  Eigen::VectorXd initial_force(Eigen::Index(3 * n_gp));
  for (Index gp = 0; gp < n_gp; ++gp) initial_force.segment<3>(Eigen::Index(3 * gp)) = solver.force_exerted_on_gridpoint(gp);
  reduced_initial_force_ = basis_.transpose() * initial_force;

  // C = (TᵀE)ᵀ (TᵀKT)⁻¹ (TᵀE): one solve per interface component, once.
  const Eigen::MatrixXd unit_loads = Eigen::MatrixXd(interface_basis_);
  const Eigen::MatrixXd responses = factorization_.solve(unit_loads);
  compliance_ = interface_basis_.transpose() * responses;
  in_situ_displacement_ = interface_basis_.transpose() * factorization_.solve(reduced_initial_force_);
}

Eigen::VectorXd CondensedElasticContinuum::interface_displacement(std::span<const double> interface_force) const {
  const Eigen::Map<const Eigen::VectorXd> force(interface_force.data(), Eigen::Index(interface_force.size()));
  return compliance_ * force + in_situ_displacement_;
}

Eigen::VectorXd CondensedElasticContinuum::reduced_load(std::span<const double> interface_force) const {
  const Eigen::Map<const Eigen::VectorXd> force(interface_force.data(), Eigen::Index(interface_force.size()));
  return reduced_initial_force_ + interface_basis_ * force;
}

std::vector<Vec3> CondensedElasticContinuum::displacement_field(std::span<const double> interface_force) const {
  const Eigen::VectorXd displacement = basis_ * factorization_.solve(reduced_load(interface_force));
  std::vector<Vec3> field(std::size_t(displacement.size() / 3));
  for (std::size_t gp = 0; gp < field.size(); ++gp) field[gp] = displacement.segment<3>(Eigen::Index(3 * gp));
  return field;
}

}  // namespace dfc::reference
