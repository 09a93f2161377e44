#pragma once
// Basic value types of the FDM solver: positions/velocities/forces and the
// symmetric tensors used for stress and strain (tension/extension positive,
// the FLAC convention; docs/theory/README.md, "Sign conventions").
#include <array>
#include <cmath>
#include <cstddef>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

#include "dfc/constitutive/sym_tensor.hpp"

namespace dfc::fdm {

using Vec3 = Eigen::Vector3d;
/// Index of a gridpoint, zone or tetrahedron.
using Index = std::size_t;

/// The models' tensor types (constitutive/), used by the solver for stress and strain.
using constitutive::Stress;
using constitutive::SymTensor;

}  // namespace dfc::fdm
